#include "deform/deformable_body.h"

#include <limits>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/log.h"
#include "core/parallel_for.h"
#include "deform/bb_element_matrices.h"
#include "deform/bb_evaluation.h"
#include "deform/bb_multi_index.h"
#include "deform/bb_node_numbering.h"
#include "deform/bb_rotated_stiffness.h"
#include "deform/contact_group_solve.h"
#include "deform/corotated_element.h"
#include "deform/deformation_gradient.h"
#include "deform/degree_hierarchy.h"
#include "deform/degree_level_assembly.h"
#include "deform/pair_contact_terms.h"
#include "deform/rotating_position_update.h"
#include "geometry/tet_mesh_boundary.h"
#include "gpu_kernels/element_gather_kernels.h"
#include "gpu_kernels/linear_tet_kernels.h"
#include "phase_timer.h"

namespace vp {
namespace {

// Speeds beyond this are treated as divergence: far above anything a game scene produces,
// far below where doubles lose all meaning.
constexpr double kMaxSpeed = 1e4;

// The energies' polar decompositions: tighter than the corotation's, since an energy's error
// is first order in the rotation's.
constexpr int kEnergyPolarIterations = 20;
constexpr double kEnergyPolarTolerance = 1e-10;

}  // namespace

Status DeformableBody::create(DeformableDesc desc, std::unique_ptr<DeformableBody>* out) {
  VP_TRY(validateDeformableDesc(desc));
  std::unique_ptr<DeformableBody> body(new DeformableBody());
  DeformableBody& b = *body;
  b.degree_ = desc.degree;
  b.nodesPerElement_ = bbNodeCount(desc.degree);
  b.lambda_ = desc.material.lameLambda();
  b.mu_ = desc.material.lameMu();
  VP_TRY(b.placeNodes(desc));
  VP_TRY(b.measureElements(desc));
  VP_TRY(b.buildStepSystem(desc));
  VP_TRY(b.buildSurfaces(desc));
  b.desc_ = std::move(desc);
  b.desc_.renderMesh.reset();  // kept once, in renderMesh_
  b.updateRenderMesh(*TaskSystem::create(TaskHooks{}, 1));
  *out = std::move(body);
  return Status::Ok;
}

Status DeformableBody::placeNodes(const DeformableDesc& desc) {
  BBNodeNumbering nodes;
  VP_TRY(numberBBNodes(desc.mesh, degree_, &nodes));
  nodeCount_ = nodes.nodeCount;
  elementNodes_ = std::move(nodes.elementNodes);
  nodeSupport_ = std::move(nodes.support);
  restX_.resize(3 * static_cast<size_t>(nodeCount_));
  x_.resize(restX_.size());
  v_.resize(restX_.size());
  for (int32_t i = 0; i < nodeCount_; ++i) {
    const Vec3& X = nodes.restPositions[i];
    const Vec3 x = desc.pose.apply(X);
    for (int k = 0; k < 3; ++k) {
      restX_[3 * i + k] = X[k];
      x_[3 * i + k] = x[k];
      v_[3 * i + k] = desc.linearVelocity[k];
    }
  }
  return Status::Ok;
}

Status DeformableBody::measureElements(const DeformableDesc& desc) {
  const TetMesh& mesh = desc.mesh;
  const int64_t elements = static_cast<int64_t>(mesh.tets.size());
  const int N = nodesPerElement_;
  restGradients_.resize(12 * static_cast<size_t>(elements));
  restVolume_.resize(static_cast<size_t>(elements));
  rotations_.resize(4 * static_cast<size_t>(elements));
  mass_.assign(static_cast<size_t>(nodeCount_), 0.0);
  double edgeSum = 0.0;
  for (int64_t e = 0; e < elements; ++e) {
    double corners[12], lumped[kBBMaxNodes];
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) corners[3 * a + k] = mesh.vertices[mesh.tets[e][a]][k];
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edgeSum += (mesh.vertices[mesh.tets[e][a]] - mesh.vertices[mesh.tets[e][b]]).norm();
    Status s = bbBarycentricGradients(corners, &restGradients_[12 * e], &restVolume_[e]);
    if (!ok(s)) return addErrorContext(s, "mesh tet " + std::to_string(e));
    // Lumped BB mass: every Bernstein function integrates to V / C(n+3, 3), all positive.
    VP_TRY(bbLumpedMass(degree_, corners, desc.material.density, lumped));
    for (int a = 0; a < N; ++a) mass_[elementNodes_[N * e + a]] += lumped[a];
    const Quat& q = desc.pose.rotation;
    double* r = &rotations_[4 * e];
    r[0] = q.w(), r[1] = q.x(), r[2] = q.y(), r[3] = q.z();
  }
  for (double m : mass_) totalMass_ += m;
  nodeSpacing_ = elements > 0 ? edgeSum / (6.0 * static_cast<double>(elements) * degree_) : 0.0;
  return Status::Ok;
}

Status DeformableBody::buildStepSystem(const DeformableDesc& desc) {
  const int64_t elements = elementCount();
  const int N = nodesPerElement_;
  // Node -> (element, corner) incidence, in element order, for the gather assembly.
  incidence_.build(nodeCount_, elementNodes_.data(), elements, N);
  elementForce_.resize(3 * static_cast<size_t>(N * elements));
  if (degree_ == 1) {
    rotatedGradients_.resize(12 * static_cast<size_t>(elements));
  } else {
    gradientPairs_.resize(144 * static_cast<size_t>(elements));
    stiffnessTerms_ = bbStiffnessTerms(degree_);
    stiffnessStructure_ = bbStiffnessStructure(degree_);
  }
  buildElementPattern(nodeCount_, elementNodes_.data(), elements, N, &matrix_, &scatter_);
  StepPreconditioner::Mesh pcMesh{degree_, elementNodes_.data(), elements, nodeCount_, restVolume_.data(),
                                  desc.material.density};
  VP_TRY(preconditioner_.build(desc.solver, pcMesh, matrix_));
  const size_t n3 = restX_.size();
  externalForce_.assign(n3, 0.0);
  fluidDrag_.assign(n3, 0.0);
  force_.resize(n3);
  rhs_.resize(n3);
  vNext_.resize(n3);
  pinned_.assign(static_cast<size_t>(nodeCount_), 0);
  held_.resize(nodeCount_);
  return Status::Ok;
}

Status DeformableBody::buildSurfaces(const DeformableDesc& desc) {
  const TetMesh& mesh = desc.mesh;
  contacts_.resize(nodeCount_);
  // Nodes this close count as touching, so a resting body keeps a stable contact set
  // instead of alternating between "just above" and "landing" every step.
  contactMargin_ = 0.02 * meanTetEdgeLength(mesh);
  const SurfaceMesh boundary = tetMeshBoundary(mesh, &surfaceNodes_);
  if (degree_ > 1) {
    // Control points of boundary edges and faces collide too (an approximation: BB control
    // points off the vertices lie near, not on, the curved surface).
    Array<uint8_t> onBoundary(static_cast<size_t>(nodeCount_), 0);
    for (int32_t v : surfaceNodes_) onBoundary[v] = 1;
    for (int32_t i = static_cast<int32_t>(mesh.vertices.size()); i < nodeCount_; ++i) {
      const auto& sup = nodeSupport_[i];
      if (onBoundary[sup[0]] && onBoundary[sup[1]] && (sup[2] < 0 || onBoundary[sup[2]])) surfaceNodes_.push_back(i);
    }
  }
  // The boundary's vertices are the first surface nodes, in the boundary's order.
  const Array<int32_t> boundaryNodes(surfaceNodes_.begin(), surfaceNodes_.begin() + boundary.vertices.size());
  Status immersed = immersion_.build(boundary, boundaryNodes, x_);
  if (!ok(immersed)) return addErrorContext(immersed, "boundary surface");
  pair_.surface.build(boundary, boundaryNodes, elementNodes_, nodesPerElement_, nodeCount_);
  pair_.friction.assign(static_cast<size_t>(nodeCount_), PairFriction());
  pair_.pendingImpulse.assign(3 * static_cast<size_t>(nodeCount_), 0.0);
  pair_.depth = kPairContactDepthEdges * meanTetEdgeLength(mesh);
  Status embedded = renderMesh_.build(mesh, desc.renderMesh ? *desc.renderMesh : boundary);
  if (!ok(embedded)) return addErrorContext(embedded, "render mesh");
  return Status::Ok;
}

bool DeformableBody::selfCollision() const {
  if (desc_.selfCollision == SelfCollision::Auto) return pair_.surface.hasInteriorNode();
  return desc_.selfCollision == SelfCollision::On;
}

PairContactBody DeformableBody::pairContactBody(double h) {
  pair_.surface.refit(x_, v_, h);
  PairContactBody b;
  b.x = &x_;
  b.v = &v_;
  b.mass = &mass_;
  b.surfaceNodes = &surfaceNodes_;
  b.surface = &pair_.surface;
  b.friction = &pair_.friction;
  b.cornerFriction = &pair_.cornerFriction;
  b.filter = desc_.filter;
  b.frictionCoefficient = desc_.material.friction;
  b.rest = contactMargin_;
  b.depth = pair_.depth;
  b.selfCollision = selfCollision();
  return b;
}

Preconditioner DeformableBody::preconditioner() const {
  return preconditioner_.kind();
}

Status DeformableBody::checkNode(const char* what, int32_t node) const {
  if (node < 0 || node >= nodeCount_)
    return fail(Status::InvalidArgument, "%s = %d: out of range [0, %d)", what, node, nodeCount_);
  return Status::Ok;
}

Status DeformableBody::setVelocities(const double* velocities, int64_t count) {
  if (count != 3 * static_cast<int64_t>(nodeCount_))
    return fail(Status::InvalidArgument, "count = %lld: must be 3 * nodeCount = %d", static_cast<long long>(count),
                3 * nodeCount_);
  for (int64_t i = 0; i < count; ++i)
    if (!std::isfinite(velocities[i]) || std::abs(velocities[i]) > kMaxSpeed)
      return fail(Status::InvalidArgument, "velocities[%lld] = %g: must be finite and below %g m/s",
                  static_cast<long long>(i), velocities[i], kMaxSpeed);
  std::copy(velocities, velocities + count, v_.begin());
  return Status::Ok;
}

void DeformableBody::heldNodes(Array<uint8_t>* out) const {
  out->assign(pinned_.begin(), pinned_.end());
  for (const Attachment& a : attachments_) (*out)[a.node] = 1;
}

Status DeformableBody::setPositions(const double* positions, int64_t count) {
  if (count != 3 * static_cast<int64_t>(nodeCount_))
    return fail(Status::InvalidArgument, "count = %lld: must be 3 * nodeCount = %d", static_cast<long long>(count),
                3 * nodeCount_);
  for (int64_t i = 0; i < count; ++i)
    if (!std::isfinite(positions[i]) || std::abs(positions[i]) > 1e6)
      return fail(Status::InvalidArgument, "positions[%lld] = %g: must be finite and within 1e6 m",
                  static_cast<long long>(i), positions[i]);
  std::copy(positions, positions + count, x_.begin());
  elasticEnergyAtX_ = -1.0;
  return Status::Ok;
}

Status DeformableBody::setMaterial(const DeformableMaterial& material) {
  VP_TRY(validateDeformableMaterial(material));
  lambda_ = material.lameLambda();
  mu_ = material.lameMu();
  const double densityRatio = material.density / desc_.material.density;
  for (double& m : mass_) m *= densityRatio;
  totalMass_ *= densityRatio;
  elasticEnergyAtX_ = -1.0;
  preconditioner_.scaleMasses(densityRatio);
  desc_.material = material;
  return Status::Ok;
}

Aabb DeformableBody::bounds() const {
  Aabb b;
  b.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  b.hi = -b.lo;
  for (size_t i = 0; i + 2 < x_.size(); i += 3) {
    const Vec3 p(x_[i], x_[i + 1], x_[i + 2]);
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

void DeformableBody::applyFluidLoads(const Vec3& gravity) {
  if (!immersion_.loaded()) return;
  Array<uint8_t> touching(static_cast<size_t>(nodeCount_), 0);
  for (const NodeContact& c : contacts_.contacts()) touching[c.node] = 1;
  immersion_.addNodeForces(x_, mass_, gravity, touching, &externalForce_);
  std::fill(fluidDrag_.begin(), fluidDrag_.end(), 0.0);
  immersion_.addNodeDrag(touching, &fluidDrag_, &externalForce_);
}

Status DeformableBody::applyForce(int32_t node, const Vec3& force) {
  VP_TRY(checkNode("node", node));
  if (!force.allFinite())
    return fail(Status::InvalidArgument, "force = (%g, %g, %g): must be finite", force.x(), force.y(), force.z());
  for (int k = 0; k < 3; ++k) externalForce_[3 * node + k] += force[k];
  return Status::Ok;
}

void DeformableBody::addContactImpulse(int32_t node, const Vec3& impulse) {
  for (int k = 0; k < 3; ++k) pair_.pendingImpulse[3 * node + k] += impulse[k];
}

Status DeformableBody::applyImpulse(int32_t node, const Vec3& impulse) {
  VP_TRY(checkNode("node", node));
  if (!impulse.allFinite())
    return fail(Status::InvalidArgument, "impulse = (%g, %g, %g): must be finite", impulse.x(), impulse.y(),
                impulse.z());
  for (int k = 0; k < 3; ++k) v_[3 * node + k] += impulse[k] / mass_[node];
  return Status::Ok;
}

Status DeformableBody::setPinned(const int32_t* nodes, int64_t count, bool pin) {
  for (int64_t i = 0; i < count; ++i) {
    char field[48];
    std::snprintf(field, sizeof field, "nodes[%lld]", static_cast<long long>(i));
    VP_TRY(checkNode(field, nodes[i]));
  }
  for (int64_t i = 0; i < count; ++i) pinned_[nodes[i]] = pin ? 1 : 0;
  // Control points of edges and faces follow their vertices: pinned when all of them are,
  // free again when one of them is unpinned (pinning a face of vertices pins the face).
  for (int32_t i = 0; i < nodeCount_; ++i) {
    const auto& sup = nodeSupport_[i];
    if (sup[0] < 0) continue;
    const bool all = pinned_[sup[0]] && pinned_[sup[1]] && (sup[2] < 0 || pinned_[sup[2]]);
    if (pin && all) pinned_[i] = 1;
    if (!pin && !all) pinned_[i] = 0;
  }
  for (int32_t i = 0; i < nodeCount_; ++i)
    if (pinned_[i])
      for (int k = 0; k < 3; ++k) v_[3 * i + k] = 0.0;
  return Status::Ok;
}

Status DeformableBody::attach(const int32_t* nodes, int64_t count, uint32_t index1, uint32_t generation,
                              const Collider& collider) {
  for (int64_t i = 0; i < count; ++i) {
    char field[48];
    std::snprintf(field, sizeof field, "nodes[%lld]", static_cast<long long>(i));
    VP_TRY(checkNode(field, nodes[i]));
  }
  const Pose pose = collider.pose();
  for (int64_t i = 0; i < count; ++i) {
    const int32_t n = nodes[i];
    const Vec3 x(x_[3 * n], x_[3 * n + 1], x_[3 * n + 2]);
    attachments_.push_back(Attachment{n, index1, generation, pose.rotation.conjugate() * (x - pose.position)});
  }
  return Status::Ok;
}

bool DeformableBody::attachedTo(int32_t node, uint32_t index1, uint32_t generation) const {
  return std::any_of(attachments_.begin(), attachments_.end(), [&](const Attachment& a) {
    return a.node == node && a.index1 == index1 && a.generation == generation;
  });
}

void DeformableBody::attachmentSprings(int32_t pairBody, const std::vector<RigidContactBody>& rigids,
                                       int32_t rigidBase, std::vector<PairContact>* out) const {
  for (const Attachment& a : attachments_) {
    const RigidContactBody* rigid = findRigidBody(rigids, a.index1, a.generation);
    if (!rigid) continue;
    const Vec3 x(x_[3 * a.node], x_[3 * a.node + 1], x_[3 * a.node + 2]);
    const Vec3 target = rigid->rotation * a.localOffset + rigid->centre;
    const double stretch = (target - x).norm();
    PairContact p;
    p.nodeBody = pairBody;
    p.node = a.node;
    p.triangleBody = rigidBase + static_cast<int32_t>(rigid - rigids.data());
    p.triangleBodyId = rigid->id;
    p.weights = Vec3(1.0, 0.0, 0.0);
    p.rigidSide = true;
    p.attachment = true;
    p.arm = target - rigid->centre;
    // The spring's push to its rest gap, K (rest − gap) n, is then K (target − x).
    p.normal = stretch > 0.0 ? Vec3((target - x) / stretch) : Vec3::UnitY();
    p.gap = -stretch;
    p.reducedMass = mass_[a.node] * rigid->mass / (mass_[a.node] + rigid->mass);
    p.nodeVelocity = Vec3(v_[3 * a.node], v_[3 * a.node + 1], v_[3 * a.node + 2]);
    p.triangleVelocities = {{rigid->pointVelocity(p.arm), Vec3::Zero(), Vec3::Zero()}};
    out->push_back(p);
  }
}

void DeformableBody::detachAll(uint32_t index1, uint32_t generation) {
  attachments_.erase(std::remove_if(attachments_.begin(), attachments_.end(),
                                    [&](const Attachment& a) { return a.index1 == index1 && a.generation == generation; }),
                     attachments_.end());
}

double DeformableBody::kineticEnergy() const {
  double e = 0.0;
  for (int32_t i = 0; i < nodeCount_; ++i)
    e += 0.5 * mass_[i] * (v_[3 * i] * v_[3 * i] + v_[3 * i + 1] * v_[3 * i + 1] + v_[3 * i + 2] * v_[3 * i + 2]);
  return e;
}

void DeformableBody::energyRotation(int64_t e, const double F[9], double R[9], double* keptRotation) const {
  // Warm-started from the element's last corotation (the energy is evaluated at or near the
  // positions it was computed at), which costs a fraction of the SVD.
  double quat[4] = {rotations_[4 * e], rotations_[4 * e + 1], rotations_[4 * e + 2], rotations_[4 * e + 3]};
  if (kernels::polarRotationIterative(F, quat, R, kEnergyPolarIterations, kEnergyPolarTolerance) < 0) {
    for (int i = 0; i < 9; ++i) R[i] = (i % 4 == 0) ? 1.0 : 0.0;  // non-finite F: the energy is too
    return;
  }
  if (keptRotation)
    for (int i = 0; i < 4; ++i) keptRotation[i] = quat[i];
}

double DeformableBody::elementElasticEnergy(int64_t e, double* keptRotation) const {
  if (degree_ > 1) {
    // ½ uᵀ K u with u = Rᵀ x − x0 in the element's unrotated frame.
    const int N = nodesPerElement_;
    double x[3 * kBBMaxNodes] = {}, x0[3 * kBBMaxNodes] = {}, F[9], R[9];  // zeroed: GCC cannot see that 3N are set
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < 3; ++i) {
        x[3 * a + i] = x_[3 * elementNodes_[N * e + a] + i];
        x0[3 * a + i] = restX_[3 * elementNodes_[N * e + a] + i];
      }
    bbAverageDeformationGradient(degree_, x, &restGradients_[12 * e], F);
    energyRotation(e, F, R, keptRotation);
    double u[3 * kBBMaxNodes], Ku[3 * kBBMaxNodes];
    kernels::unrotatedDisplacement(N, R, x, x0, u);
    kernels::bbStiffnessApply(degree_, stiffnessStructure_.view(), &restGradients_[12 * e], restVolume_[e], lambda_,
                              mu_, u, Ku);
    double uKu = 0.0;
    for (int i = 0; i < 3 * N; ++i) uKu += u[i] * Ku[i];
    return 0.5 * uKu;
  }
  double x[12], F[9], R[9];
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) x[3 * a + i] = x_[3 * elementNodes_[4 * e + a] + i];
  bbAverageDeformationGradient(1, x, &restGradients_[12 * e], F);
  energyRotation(e, F, R, keptRotation);
  double eps[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double sij = 0.0, sji = 0.0;
      for (int k = 0; k < 3; ++k) sij += R[3 * k + i] * F[3 * k + j], sji += R[3 * k + j] * F[3 * k + i];
      eps[3 * i + j] = 0.5 * (sij + sji) - (i == j ? 1.0 : 0.0);
    }
  double epsEps = 0.0;
  for (double v : eps) epsEps += v * v;
  const double trace = eps[0] + eps[4] + eps[8];
  return restVolume_[e] * (mu_ * epsEps + 0.5 * lambda_ * trace * trace);
}

double DeformableBody::elasticEnergy(TaskSystem& tasks) const {
  return parallelReduce<double>(tasks, elementCount(), 256, [&](int64_t begin, int64_t end) {
    double sum = 0.0;
    for (int64_t e = begin; e < end; ++e) sum += elementElasticEnergy(e);
    return sum;
  });
}

double DeformableBody::elasticEnergyKeepingRotations(TaskSystem& tasks) {
  // The same chunks and sum order as elasticEnergy; each element writes only its own rotation.
  return parallelReduce<double>(tasks, elementCount(), 256, [&](int64_t begin, int64_t end) {
    double sum = 0.0;
    for (int64_t e = begin; e < end; ++e) sum += elementElasticEnergy(e, &rotations_[4 * e]);
    return sum;
  });
}

void DeformableBody::elasticForces(TaskSystem& tasks, Array<double>* out) {
  corotateAndAssemble(tasks, 1.0);
  out->assign(force_.begin(), force_.end());
}

void DeformableBody::updateRenderMesh(TaskSystem& tasks) {
  renderMesh_.update(tasks, degree_, nodesPerElement_, elementNodes_, x_);
}

void DeformableBody::refreshPreconditioner(TaskSystem& tasks, double massScale) {
  preconditioner_.refresh(tasks, matrix_, x_.data(), held_, gradientPairs_.data(), massScale);
}

double DeformableBody::elasticWaveCrossings(double h) const {
  if (!(nodeSpacing_ > 0.0)) return 0.0;
  const DeformableMaterial& m = desc_.material;
  const double waveSpeed = std::sqrt((m.lameLambda() + 2.0 * m.lameMu()) / m.density);
  return std::sqrt((h * h + h * m.stiffnessDamping) / massScale(h)) * waveSpeed / nodeSpacing_;
}

void DeformableBody::choosePreconditioner(double h) {
  // On the device block-Jacobi (its solve reads those blocks only), as for a short step.
  preconditioner_.chooseForStep(deviceSolve_ ? 0.0 : elasticWaveCrossings(h), matrix_);
}

void DeformableBody::contactImpulses(TaskSystem& tasks, Array<Vec3>* impulses) {
  // (A v' − b) at a constrained node is the impulse the constraint applied there.
  cg_.q.resize(vNext_.size());
  matrix_.multiply(tasks, vNext_.data(), cg_.q.data());
  const Array<NodeContact>& contacts = contacts_.contacts();
  impulses->resize(contacts.size());
  for (size_t c = 0; c < contacts.size(); ++c) {
    const int32_t i = contacts[c].node;
    for (int k = 0; k < 3; ++k) (*impulses)[c][k] = cg_.q[3 * i + k] + pairCouplingAt(3 * i + k) - rhs_[3 * i + k];
  }
}

// Pass 2 of assembly, per node: one matrix block row each (gpu_kernels/element_gather_kernels.h),
// gathering the forces and, through addBlock(element, corner a, corner b, block), the stiffness
// blocks of the incident elements. Gathering keeps the writes in matrix order; scattering
// element by element touched the 20 MB matrix of a large mesh at random.
template <class AddBlock>
void DeformableBody::gatherRows(TaskSystem& tasks, int64_t grain, const AddBlock& addBlock) {
  const kernels::ElementIncidenceView incidence{incidence_.start.data(), incidence_.element.data(),
                                                incidence_.corner.data()};
  parallelFor(tasks, nodeCount_, grain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      kernels::gatherElementRow(i, nodesPerElement_, matrix_.rowStart.data(), incidence, scatter_.data(),
                                elementForce_.data(), addBlock, matrix_.values.data(), force_.data());
  });
}

gpu::ElementAssemblyView DeformableBody::elementAssemblyView() const {
  gpu::ElementAssemblyView view;
  view.degree = degree_;
  view.nodes = nodeCount_;
  view.elements = elementCount();
  view.elementNodes = elementNodes_.data();
  view.restGradients = restGradients_.data();
  view.restVolume = restVolume_.data();
  view.lambda = lambda_;
  view.mu = mu_;
  view.rowStart = matrix_.rowStart.data();
  view.incidence = {incidence_.start.data(), incidence_.element.data(), incidence_.corner.data()};
  view.scatter = scatter_.data();
  if (degree_ > 1) {
    view.restPositions = restX_.data();
    view.structure = stiffnessStructure_.view();
    view.nodeCorners = bbNodeCornerMasks(degree_);
    view.terms = stiffnessTerms_.view();
  }
  return view;
}

void DeformableBody::corotateAndAssemble(TaskSystem& tasks, double stiffnessScale) {
  if (degree_ > 1) return corotateAndAssembleBB(tasks, stiffnessScale);
  // Pass 1, per element: rotation, force and rotated gradients into element buffers.
  parallelFor(tasks, elementCount(), 512, [&](int64_t begin, int64_t end) {
    for (int64_t e = begin; e < end; ++e) {
      const int32_t* nodes = &elementNodes_[4 * e];
      double x[12];
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) x[3 * a + i] = x_[3 * nodes[a] + i];
      kernels::corotateLinearTet(x, &restGradients_[12 * e], restVolume_[e], lambda_, mu_, &rotations_[4 * e],
                        &elementForce_[12 * e], &rotatedGradients_[12 * e]);
    }
  });
  gatherRows(tasks, 256, [&](int64_t e, int a, int b, double* block) {
    kernels::addLinearTetBlock(&rotatedGradients_[12 * e], &restGradients_[12 * e], a, b, restVolume_[e], lambda_, mu_,
                      stiffnessScale, block);
  });
}

void DeformableBody::corotateAndAssembleBB(TaskSystem& tasks, double stiffnessScale) {
  const int N = nodesPerElement_;
  const uint8_t* nodeCorners = bbNodeCornerMasks(degree_);
  const kernels::BBStiffnessTermsView terms = stiffnessTerms_.view();
  const kernels::BBStiffnessStructureView structure = stiffnessStructure_.view();
  // Pass 1, per element: one rotation from the volume-averaged deformation gradient and the
  // corotated force −R K (Rᵀ x − x0) with the rest K applied unstored, and the 16 rotated gradient-pair
  // matrices the gather sums into each R K_ab Rᵀ (deform/bb_rotated_stiffness.h).
  parallelFor(tasks, elementCount(), 64, [&](int64_t begin, int64_t end) {
    for (int64_t e = begin; e < end; ++e) {
      const int32_t* nodes = &elementNodes_[N * e];
      double x[3 * kBBMaxNodes], x0[3 * kBBMaxNodes];
      for (int a = 0; a < N; ++a)
        for (int i = 0; i < 3; ++i) x[3 * a + i] = x_[3 * nodes[a] + i], x0[3 * a + i] = restX_[3 * nodes[a] + i];
      kernels::corotateBBElement(degree_, nodeCorners, structure, x, x0, &restGradients_[12 * e], restVolume_[e],
                                 lambda_, mu_, stiffnessScale, &rotations_[4 * e], &elementForce_[3 * N * e],
                                 &gradientPairs_[144 * e]);
    }
  });
  gatherRows(tasks, 64, [&](int64_t e, int a, int b, double* block) {
    kernels::addBBRotatedBlock(terms, &gradientPairs_[144 * e], N, a, b, block);
  });
}

void DeformableBody::restoreStepStart() {
  x_.assign(backupX_.begin(), backupX_.end());
  elasticEnergyAtX_ = -1.0;
  v_.assign(backupV_.begin(), backupV_.end());
  // Rotations warm starts may be garbage now; restart them from identity.
  for (int64_t e = 0; e < elementCount(); ++e) {
    double* r = &rotations_[4 * e];
    r[0] = 1, r[1] = r[2] = r[3] = 0;
  }
}

namespace {

// Per-node sums of a solved step (core/step_energy.h), reduced in chunk order.
struct NodeWork {
  double kineticStart = 0.0, kineticEnd = 0.0, gravity = 0.0, applied = 0.0;
  NodeWork& operator+=(const NodeWork& o) {
    kineticStart += o.kineticStart, kineticEnd += o.kineticEnd, gravity += o.gravity, applied += o.applied;
    return *this;
  }
};

}  // namespace

StepEnergy DeformableBody::solvedStepEnergy(TaskSystem& tasks, double h, const Vec3& gravity,
                                           const std::vector<PairContact>* pairs, int32_t pairBody,
                                           const PairVelocities& solved) {
  if (elasticEnergyAtX_ < 0.0) elasticEnergyAtX_ = elasticEnergy(tasks);
  const NodeWork w = parallelReduce<NodeWork>(tasks, nodeCount_, 1024, [&](int64_t begin, int64_t end) {
    NodeWork sum;
    for (int64_t i = begin; i < end; ++i) {
      const double* v = &v_[3 * i];
      const double* vn = &vNext_[3 * i];
      const double m = mass_[i];
      double impulse[3] = {0.0, 0.0, 0.0};  // A v' − b: what a pin, attachment or contact applied
      if (held_.kind[i] != NodeConstraints::kFree) {
        for (int32_t k = matrix_.rowStart[i]; k < matrix_.rowStart[i + 1]; ++k) {
          const double* block = &matrix_.values[9 * static_cast<int64_t>(k)];
          const double* vc = &vNext_[3 * static_cast<int64_t>(matrix_.columns[k])];
          for (int r = 0; r < 3; ++r) impulse[r] += block[3 * r] * vc[0] + block[3 * r + 1] * vc[1] + block[3 * r + 2] * vc[2];
        }
        for (int r = 0; r < 3; ++r) impulse[r] += pairCouplingAt(3 * i + r) - rhs_[3 * i + r];
      }
      for (int k = 0; k < 3; ++k) {
        sum.kineticStart += 0.5 * m * v[k] * v[k];
        sum.kineticEnd += 0.5 * m * vn[k] * vn[k];
        sum.gravity += h * m * gravity[k] * vn[k];
        sum.applied += (h * externalForce_[3 * i + k] + pair_.pendingImpulse[3 * i + k] + impulse[k]) * vn[k];
        sum.applied -= h * fluidDrag_[3 * i + k] * vn[k] * vn[k];
      }
    }
    return sum;
  });
  StepEnergy e;
  e.kineticStart = w.kineticStart;
  e.kineticEnd = w.kineticEnd;
  e.elasticStart = elasticEnergyAtX_;
  e.gravityWork = w.gravity;
  e.appliedWork = w.applied;
  const Array<NodeContact>& contacts = contacts_.contacts();
  for (size_t c = 0; c < contacts.size(); ++c) {  // kinetic friction, an impulse on the rhs
    const double* vn = &vNext_[3 * static_cast<int64_t>(contacts[c].node)];
    e.appliedWork += contacts_.frictionImpulses()[c].dot(Vec3(vn[0], vn[1], vn[2]));
  }
  if (pairs) e.appliedWork += pairContactWork(*pairs, pairBody, h, vNext_, solved);
  return e;
}

bool DeformableBody::stepBlewUp(TaskSystem& tasks, StepEnergy energy, bool solveReachedFloor) {
  for (double v : v_)
    if (!std::isfinite(v) || std::abs(v) > kMaxSpeed) return true;
  energy.elasticEnd = elasticEnergyKeepingRotations(tasks);
  // A solve cut short above its floor is inexact by the budget's choice, not blown up.
  if (solveReachedFloor && StepEnergyGuard::blewUp(energy, totalMass_)) {
    log(LogLevel::Warning, "deformable step blew up: its energy rose %g J beyond the %g J its work explains "
        "(kinetic %g -> %g, elastic %g -> %g); restored", StepEnergyGuard::unexplainedGain(energy),
        energy.gravityWork + energy.appliedWork, energy.kineticStart, energy.kineticEnd, energy.elasticStart,
        energy.elasticEnd);
    return true;
  }
  elasticEnergyAtX_ = energy.elasticEnd;
  return false;
}

void DeformableBody::abandonStep() {
  if (stepBegun_) restoreStepStart();
  stepBegun_ = false;
  std::fill(externalForce_.begin(), externalForce_.end(), 0.0);
  std::fill(fluidDrag_.begin(), fluidDrag_.end(), 0.0);
}

void DeformableBody::step(const DeformableStepInput& in, ActorStats* stats) {
  PhaseTimer timer(in.deadline, stats);
  std::vector<ContactGroupMember> alone{{this, &in, &timer, stats}};
  stepContactGroup(alone);
}

void DeformableBody::beginStep(const DeformableStepInput& in, PhaseTimer& timer) {
  backupX_.assign(x_.begin(), x_.end());
  backupV_.assign(v_.begin(), v_.end());
  stepBegun_ = true;
  pair_.coupling.clear();
  holdNodes(in);
  timer.lap(Phase::Contacts);
  corotateAndAssemble(*in.tasks, in.dt * desc_.material.stiffnessDamping + in.dt * in.dt);
  timer.lap(Phase::Corotate);
  if (in.pairContacts) addPairContactStiffness(*in.pairContacts, in.pairBody, in.dt, &matrix_);
  assembleStepSystem(in);
  if (in.pairContacts) addPairContactRhs(*in.pairContacts, in.pairBody, in.dt, &rhs_);
  for (size_t k = 0; k < rhs_.size(); ++k) rhs_[k] += pair_.pendingImpulse[k];
  timer.lap(Phase::Assemble);
}

void DeformableBody::finishStep(const DeformableStepInput& in, bool reachedFloor, const PairVelocities& solved,
                                PhaseTimer& timer, ActorStats* stats) {
  if (in.pairContacts)
    updatePairFriction(*in.pairContacts, in.pairBody, in.dt, vNext_, solved, &pair_.friction, &pair_.cornerFriction);
  integrateAndGuard(in, reachedFloor, solved, stats);  // its energy passes are timed with the embedding
  std::fill(externalForce_.begin(), externalForce_.end(), 0.0);
  std::fill(fluidDrag_.begin(), fluidDrag_.end(), 0.0);
  std::fill(pair_.pendingImpulse.begin(), pair_.pendingImpulse.end(), 0.0);
  updateRenderMesh(*in.tasks);
  timer.lap(Phase::Embed);
  stepBegun_ = false;
}

void DeformableBody::discardStep(TaskSystem& tasks) {
  restoreStepStart();
  reactions_.clear();
  updateRenderMesh(tasks);
}

void DeformableBody::holdNodes(const DeformableStepInput& in) {
  // Pinned nodes keep zero velocity, attached ones the velocity that brings them to their
  // collider-carried target by the end of the step; contacts ignore both.
  const double h = in.dt;
  held_.clear();
  vNext_.assign(v_.begin(), v_.end());  // warm start
  for (int32_t i = 0; i < nodeCount_; ++i)
    if (pinned_[i]) {
      held_.kind[i] = NodeConstraints::kFixed;
      for (int k = 0; k < 3; ++k) vNext_[3 * i + k] = 0.0;
    }
  attachments_.erase(std::remove_if(attachments_.begin(), attachments_.end(),
                                    [&](const Attachment& a) { return !in.collider || !in.collider(a.index1, a.generation); }),
                     attachments_.end());
  auto solvedWith = [&](const Attachment& a) {
    return in.rigidBodies && findRigidBody(*in.rigidBodies, a.index1, a.generation);
  };
  for (const Attachment& a : attachments_) {
    if (solvedWith(a)) continue;  // a spring of the group's solve (attachmentSprings)
    const Pose pose = in.collider(a.index1, a.generation)->pose();
    const Vec3 target = pose.apply(a.localOffset);
    held_.kind[a.node] = NodeConstraints::kFixed;
    for (int k = 0; k < 3; ++k) vNext_[3 * a.node + k] = (target[k] - x_[3 * a.node + k]) / h;
  }
  contacts_.begin(x_, v_, in.contactLookahead ? *in.contactLookahead : v_, surfaceNodes_, in.colliders, h,
                  desc_.material.friction, contactMargin_, &held_, &vNext_);
}

double DeformableBody::massScale(double h) const { return 1.0 + h * desc_.material.massDamping; }

void DeformableBody::assembleStepSystem(const DeformableStepInput& in) {
  // (M (1 + h α) + h C + (h β + h²) K) v' = M v + h (f + M g + f_ext), the stiffness part
  // assembled; C the fluids' viscous drag.
  const double h = in.dt;
  const double scale = massScale(h);
  parallelFor(*in.tasks, nodeCount_, 1024, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      double* diag = &matrix_.values[9 * static_cast<int64_t>(matrix_.diagonal[i])];
      const double m = mass_[i];
      for (int k = 0; k < 3; ++k) diag[4 * k] += scale * m + h * fluidDrag_[3 * i + k];
      for (int k = 0; k < 3; ++k)
        rhs_[3 * i + k] = m * v_[3 * i + k] + h * (force_[3 * i + k] + m * in.gravity[k] + externalForce_[3 * i + k]);
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> inv(preconditioner_.inverseDiagonal(i));
      inv = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(diag).inverse();
    }
  });
  contacts_.addFriction(&rhs_);
  if (deviceSolve_) deviceSolve_->matrixChanged();
}

CgResult DeformableBody::solveLinearSystem(const DeformableStepInput& in, const LinearSystem& system,
                                          const CgSettings& settings, double massScale) {
  const double floor = desc_.solver.targetResidual;
  if (deviceSolve_) {
    CgResult result;
    if (ok(deviceSolve_->solve(matrix_, preconditioner_.inverseDiagonal(0), held_, rhs_.data(), vNext_.data(),
                               settings, in.deadline, floor, in.floorDeadline, &result)))
      return result;
    log(LogLevel::Warning, "deformable '%s': %s; its solves run on the CPU from now on", desc_.name.c_str(),
        lastError());
    deviceSolve_.reset();
    choosePreconditioner(in.dt);
    if (preconditioner_.needsRefresh()) refreshPreconditioner(*in.tasks, massScale);
  }
  return solveConjugateGradient(*in.tasks, system, rhs_.data(), vNext_.data(), settings, in.deadline, cg_, floor,
                                in.floorDeadline);
}

Status DeformableBody::setSolveOnDevice(bool onDevice) {
  if (!onDevice) {
    deviceSolve_.reset();
    return Status::Ok;
  }
  if (deviceSolve_) return Status::Ok;
  return DeviceStepSolve::create(matrix_, &deviceSolve_);
}

bool DeformableBody::pinnedOrAttached() const {
  return !attachments_.empty() || std::any_of(pinned_.begin(), pinned_.end(), [](uint8_t p) { return p != 0; });
}

void DeformableBody::integrateAndGuard(const DeformableStepInput& in, bool solveReachedFloor,
                                       const PairVelocities& solved, ActorStats* stats) {
  StepEnergy energy = solvedStepEnergy(*in.tasks, in.dt, in.gravity, in.pairContacts, in.pairBody, solved);
  if (pinnedOrAttached()) {
    moveAlongStraightLines(in.dt, vNext_, &x_, &v_);
  } else {
    moveRotatingBody(mass_, in.dt, vNext_, &x_, &v_);
    energy.kineticEnd = kineticEnergy();  // the turn's spin correction may change it a little
  }
  stats->diverged = stepBlewUp(*in.tasks, energy, solveReachedFloor);
  if (stats->diverged) {
    restoreStepStart();
    reactions_.clear();
  }
}

void DeformableBody::recordReactions(TaskSystem& tasks, const DeformableStepInput& in, const PairVelocities& solved) {
  reactions_.clear();
  rigidContacts_.clear();
  const double h = in.dt;
  const Array<NodeContact>& contacts = contacts_.contacts();
  auto dynamic = [&](const NodeContact& c) {
    for (const ContactCollider& cc : in.colliders)
      if (cc.index1 == c.colliderIndex1 && cc.generation == c.colliderGeneration) return cc.dynamic;
    return false;
  };
  if (std::any_of(contacts.begin(), contacts.end(), dynamic)) {
    Array<Vec3> impulses;
    contactImpulses(tasks, &impulses);
    for (size_t c = 0; c < contacts.size(); ++c) {
      if (!dynamic(contacts[c])) continue;
      const int32_t i = contacts[c].node;
      // The node where the step leaves it, touching the collider.
      Vec3 point;
      for (int k = 0; k < 3; ++k) point[k] = x_[3 * i + k] + h * vNext_[3 * i + k];
      reactions_.push_back({contacts[c].colliderIndex1, contacts[c].colliderGeneration, point, -impulses[c]});
    }
  }
  if (!in.pairContacts) return;
  for (const PairContact& p : *in.pairContacts) {
    const bool onNode = p.rigidSide && p.nodeBody == in.pairBody;
    const bool onTriangle = p.rigidNode && p.triangleBody == in.pairBody;
    if (!p.coupled || !(onNode || onTriangle)) continue;
    // Equal and opposite at the contact point the solve's J used: momentum and angular momentum
    // conserved to rounding, however far the solve got.
    const Vec3 impulse = coupledNodeImpulse(p, h, solved);
    const RigidContactBody& rigid = in.rigidBody(onNode ? p.triangleBody : p.nodeBody);
    // A rigid corner is the node side: it takes the node's impulse.
    reactions_.push_back({rigid.id.index1, rigid.id.generation, rigid.centre + p.arm, onNode ? -impulse : impulse});
    if (p.attachment || !(impulse.dot(p.normal) > 0.0)) continue;
    NodeContact touch;
    // The body's node a corner pushes hardest (the triangle's with the largest weight), and the
    // normal out of the rigid body either way.
    Eigen::Index corner = 0;
    p.weights.maxCoeff(&corner);
    touch.node = onNode ? p.node : p.triangleNodes[static_cast<size_t>(corner)];
    touch.normal = onNode ? p.normal : Vec3(-p.normal);
    touch.colliderVelocity = rigid.pointVelocity(p.arm);
    touch.friction = p.friction;
    touch.colliderIndex1 = rigid.id.index1;
    touch.colliderGeneration = rigid.id.generation;
    rigidContacts_.push_back(touch);
  }
}

DeformableState DeformableBody::saveState() const {
  DeformableState s;
  s.x = x_;
  s.v = v_;
  s.externalForce = externalForce_;
  s.rotations = rotations_;
  contacts_.saveTo(&s);
  s.renderPositions = renderMesh_.positions();
  s.renderNormals = renderMesh_.normals();
  s.schedule = schedule_;
  s.pairFriction = pair_.friction;
  s.cornerFriction = pair_.cornerFriction;
  s.pendingImpulse = pair_.pendingImpulse;
  return s;
}

void DeformableBody::restoreState(DeformableState&& s) {
  x_ = std::move(s.x);
  elasticEnergyAtX_ = -1.0;
  v_ = std::move(s.v);
  externalForce_ = std::move(s.externalForce);
  rotations_ = std::move(s.rotations);
  contacts_.restoreFrom(&s);
  renderMesh_.restore(std::move(s.renderPositions), std::move(s.renderNormals));
  schedule_ = s.schedule;
  pair_.friction = std::move(s.pairFriction);
  pair_.cornerFriction = std::move(s.cornerFriction);
  pair_.pendingImpulse = std::move(s.pendingImpulse);
}

}  // namespace vp
