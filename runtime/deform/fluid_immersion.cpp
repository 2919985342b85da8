// A deformable's surface in the fluids and their loads on it (see fluid_immersion.h).
#include "deform/fluid_immersion.h"

#include <algorithm>

#include "deform/rigid_view.h"

namespace vp {
namespace {

Vec3 nodeVector(const Array<double>& a, size_t node) { return RigidView::at(a, node); }

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
  hydrostaticForces_.assign(vertexNode.size(), Vec3::Zero());
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
  forces_.assign(vertexNode_.size(), Vec3::Zero());
  hydrostaticForces_.assign(vertexNode_.size(), Vec3::Zero());
  drag_ = VertexDrag{};
  addedMass_ = 0.0;
  reaction_ = spinReaction_ = Vec3::Zero();
  loaded_ = false;
}

bool FluidImmersion::addHydrostaticLoad(const Array<Vec3>& vertexForces) {
  if (vertexForces.size() != hydrostaticForces_.size()) return false;
  for (size_t i = 0; i < vertexForces.size(); ++i) hydrostaticForces_[i] += vertexForces[i];
  loaded_ = true;
  return true;
}

bool FluidImmersion::addLoad(const Array<Vec3>& dynamicForces, double addedMass, const SolidAcceleration& seen,
                             const VertexDrag& drag) {
  if (dynamicForces.size() != forces_.size() || !(addedMass >= 0.0)) return false;
  if (!drag.empty()) {
    const bool sized = drag.coefficient.size() == forces_.size() && drag.atRest.size() == forces_.size();
    if (!sized || !std::all_of(drag.coefficient.begin(), drag.coefficient.end(),
                               [](const Vec3& c) { return (c.array() >= 0.0).all(); }))
      return false;
    if (drag_.empty()) {
      drag_.coefficient.assign(forces_.size(), Vec3::Zero());
      drag_.atRest.assign(forces_.size(), Vec3::Zero());
    }
    for (size_t i = 0; i < forces_.size(); ++i) {
      drag_.coefficient[i] += drag.coefficient[i];
      drag_.atRest[i] += drag.atRest[i];
    }
  }
  for (size_t i = 0; i < forces_.size(); ++i) forces_[i] += dynamicForces[i];
  addedMass_ += addedMass;
  reaction_ += addedMass * seen.linear;
  spinReaction_ += addedMass * seen.angular;
  loaded_ = true;
  return true;
}

Array<Eigen::Vector3d> FluidImmersion::vertices(const Array<double>& x) const {
  Array<Eigen::Vector3d> out(vertexNode_.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = nodeVector(x, static_cast<size_t>(vertexNode_[i]));
  return out;
}

SolidMotion FluidImmersion::rigidMotion(const Array<double>& x, const Array<double>& v, const Array<double>& mass) {
  const RigidView body(x, &v, mass);
  if (!(body.mass > 0.0)) return SolidMotion{};
  return SolidMotion{body.momentum / body.mass, body.solveInertia(body.angularMomentum)};
}

void FluidImmersion::addNodeForces(const Array<double>& x, const Array<double>& mass, const Vec3& gravity,
                                   const Array<uint8_t>& touching, Array<double>* force) const {
  const RigidView body(x, nullptr, mass);
  if (!loaded_ || !(body.mass > 0.0)) return;
  Array<double> f(3 * mass.size(), 0.0);
  Vec3 net = Vec3::Zero(), torque = Vec3::Zero(), dynamicNet = Vec3::Zero(), dynamicTorque = Vec3::Zero();
  for (size_t v = 0; v < forces_.size(); ++v) {
    const int32_t node = vertexNode_[v];
    const Vec3 dynamic = touching[node] ? Vec3::Zero() : forces_[v], load = dynamic + hydrostaticForces_[v];
    const Vec3 r = nodeVector(x, static_cast<size_t>(node)) - body.centre;
    for (int k = 0; k < 3; ++k) f[3 * node + k] += load[k];
    net += load;
    torque += r.cross(load);
    dynamicNet += dynamic;
    dynamicTorque += r.cross(dynamic);
  }
  const double k = addedMass_ / body.mass;
  const Vec3 reaction = shownReaction(reaction_, dynamicNet);
  const Vec3 spinReaction = shownReaction(body.inertia * spinReaction_ / body.mass, dynamicTorque);
  const Vec3 stabilizedNet = (net + reaction - addedMass_ * gravity) / (1.0 + k);
  const Vec3 stabilizedTorque = (torque + spinReaction) / (1.0 + k);
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

void FluidImmersion::addNodeDrag(const Array<uint8_t>& touching, Array<double>* drag, Array<double>* force) const {
  if (drag_.empty()) return;
  for (size_t v = 0; v < vertexNode_.size(); ++v) {
    const int32_t node = vertexNode_[v];
    if (touching[node]) continue;
    for (int k = 0; k < 3; ++k) {
      (*drag)[3 * node + k] += drag_.coefficient[v][k];
      (*force)[3 * node + k] += drag_.atRest[v][k];
    }
  }
}

}  // namespace vp
