// A deformable's surface in the fluids and their loads on it (see fluid_immersion.h).
#include "deform/fluid_immersion.h"

#include <Eigen/Dense>

namespace vp {
namespace {

Vec3 nodeVector(const Array<double>& a, size_t node) { return Vec3(a[3 * node], a[3 * node + 1], a[3 * node + 2]); }

// The body as a rigid body: mass, centre of mass, inertia about it, momentum and angular momentum.
struct RigidView {
  double mass = 0.0;
  Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero(), angularMomentum = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();

  RigidView(const Array<double>& x, const Array<double>* v, const Array<double>& m) {
    for (size_t i = 0; i < m.size(); ++i) mass += m[i], centre += m[i] * nodeVector(x, i);
    if (!(mass > 0.0)) return;
    centre /= mass;
    for (size_t i = 0; i < m.size(); ++i) {
      const Vec3 r = nodeVector(x, i) - centre;
      inertia += m[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
      if (v == nullptr) continue;
      momentum += m[i] * nodeVector(*v, i);
      angularMomentum += m[i] * r.cross(nodeVector(*v, i));
    }
  }
  // I^-1 b; zero where the inertia is singular (a body of collinear nodes cannot spin).
  Vec3 solveInertia(const Vec3& b) const {
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(inertia);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-12 * inertia.trace())) return Vec3::Zero();
    return ldlt.solve(b);
  }
};

}  // namespace

Status FluidImmersion::build(const SurfaceMesh& boundary, const Array<int32_t>& vertexNode, const Array<double>& x) {
  vertexNode_ = vertexNode;
  positions_.resize(vertexNode.size());
  for (size_t i = 0; i < vertexNode.size(); ++i) positions_[i] = nodeVector(x, static_cast<size_t>(vertexNode[i]));
  Array<Eigen::Vector3i> triangles;
  triangles.reserve(boundary.triangles.size());
  for (const auto& t : boundary.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto surface = std::make_shared<PreparedCollider>();
  VP_TRY(prepareDeformingSurface(positions_, triangles, surface.get()));
  surface_ = std::move(surface);
  forces_.assign(vertexNode.size(), Vec3::Zero());
  return Status::Ok;
}

std::shared_ptr<const PreparedCollider> FluidImmersion::surface(const Array<double>& x, const Array<double>& v) {
  const size_t n = vertexNode_.size();
  positions_.resize(n);
  velocities_.resize(n);
  bool moved = false;
  for (size_t i = 0; i < n; ++i) {
    positions_[i] = nodeVector(x, static_cast<size_t>(vertexNode_[i]));
    velocities_[i] = nodeVector(v, static_cast<size_t>(vertexNode_[i]));
    moved = moved || positions_[i] != surface_->shape.meshVertices[i] || velocities_[i] != surface_->vertexVelocities[i];
  }
  if (!moved) return surface_;
  // A fluid step in progress keeps the old surface; this one moves a copy.
  if (surface_.use_count() > 1) surface_ = std::make_shared<PreparedCollider>(*surface_);
  setDeformingSurface(surface_.get(), positions_, velocities_);
  return surface_;
}

void FluidImmersion::clearLoads() {
  std::fill(forces_.begin(), forces_.end(), Vec3::Zero());
  addedMass_ = 0.0;
  loaded_ = false;
}

bool FluidImmersion::addLoad(const Array<Vec3>& vertexForces, double addedMass) {
  if (vertexForces.size() != forces_.size() || !(addedMass >= 0.0)) return false;
  for (size_t i = 0; i < forces_.size(); ++i) forces_[i] += vertexForces[i];
  addedMass_ += addedMass;
  loaded_ = true;
  return true;
}

void FluidImmersion::trackVelocity(const Array<double>& x, const Array<double>& v, const Array<double>& mass,
                                   double h) {
  const RigidView body(x, &v, mass);
  if (!(body.mass > 0.0)) return;
  const Vec3 velocity = body.momentum / body.mass, spin = body.solveInertia(body.angularMomentum);
  const bool stepped = tracking_.stepDt > 0.0;  // a first step has no last one
  tracking_.acceleration = stepped ? Vec3((velocity - tracking_.velocity) / tracking_.stepDt) : Vec3::Zero();
  tracking_.spinAcceleration = stepped ? Vec3((spin - tracking_.spin) / tracking_.stepDt) : Vec3::Zero();
  tracking_.velocity = velocity;
  tracking_.spin = spin;
  tracking_.stepDt = h;
}

void FluidImmersion::addNodeForces(const Array<double>& x, const Array<double>& mass, double h, const Vec3& gravity,
                                   const Array<uint8_t>& touching, Array<double>* force) const {
  const RigidView body(x, nullptr, mass);
  if (!loaded_ || !(body.mass > 0.0) || !(h > 0.0)) return;
  Array<double> f(3 * mass.size(), 0.0);
  for (size_t v = 0; v < forces_.size(); ++v)
    if (!touching[vertexNode_[v]])
      for (int k = 0; k < 3; ++k) f[3 * vertexNode_[v] + k] += forces_[v][k];
  Vec3 net = Vec3::Zero(), torque = Vec3::Zero();
  for (size_t i = 0; i < mass.size(); ++i) {
    net += nodeVector(f, i);
    torque += (nodeVector(x, i) - body.centre).cross(nodeVector(f, i));
  }
  const double k = addedMass_ / body.mass;
  const Vec3 stabilizedNet = (net + addedMass_ * (tracking_.acceleration - gravity)) / (1.0 + k);
  const Vec3 stabilizedTorque = (torque + k * body.inertia * tracking_.spinAcceleration) / (1.0 + k);
  // Per node: the rest (f minus its rigid part) scaled, plus the stabilized rigid part.
  const Vec3 linear = net / body.mass, angular = body.solveInertia(torque);
  const Vec3 linearOut = stabilizedNet / body.mass, angularOut = body.solveInertia(stabilizedTorque);
  for (size_t i = 0; i < mass.size(); ++i) {
    const Vec3 r = nodeVector(x, i) - body.centre;
    const Vec3 rest = nodeVector(f, i) - mass[i] * (linear + angular.cross(r));
    const Vec3 out = rest / (1.0 + k) + mass[i] * (linearOut + angularOut.cross(r));
    for (int c = 0; c < 3; ++c) (*force)[3 * i + c] += out[c];
  }
}

}  // namespace vp
