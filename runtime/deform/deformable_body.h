// A deformable volume actor: corotational linear elasticity on a tet mesh, integrated with
// backward Euler and one linear solve per step,
//   (M + h D + h² K) v' = M v + h (f(x) + f_ext),   D = αM + βK,   x' = x + h v',
// where f(x) is the corotated elastic force and K its (rotated) stiffness at x. The matrix is
// assembled in 3x3 blocks, element pass then node gather (parallel, deterministic), and
// solved by CG preconditioned with aggregation multigrid (p-multigrid over the degrees for
// quadratic and cubic elements, block-Jacobi on small meshes),
// warm-started from the current velocity, within the actor's share of the frame budget. Pinned and attached nodes are velocity constraints
// handled inside CG by filtering (Baraff & Witkin 1998), not by penalties.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "core/allocator.h"
#include "collide/collider.h"
#include "core/budget_clock.h"
#include "core/slot_map.h"
#include "core/task_system.h"
#include "deform/deformable_desc.h"
#include "core/step_energy.h"
#include "deform/bb_rotated_stiffness.h"
#include "deform/contact_active_set.h"
#include "deform/contact_surface.h"
#include "deform/deformable_contacts.h"
#include "deform/device_step_solve.h"
#include "gpu_kernels/device_element_assembly.h"
#include "deform/node_constraints.h"
#include "deform/pair_contact_terms.h"
#include "deform/pair_contacts.h"
#include "deform/step_preconditioner.h"
#include "deform/degree_level_assembly.h"
#include "deform/element_incidence.h"
#include "deform/embedded_render_mesh.h"
#include "deform/fluid_immersion.h"
#include "frame_plan.h"
#include "phase_timer.h"
#include "geometry/embedding.h"
#include "geometry/mesh_quality.h"
#include "geometry/refit_bvh.h"
#include "linalg/aggregation_multigrid.h"
#include "linalg/block_sparse_matrix.h"
#include "linalg/conjugate_gradient.h"
#include "linalg/p_multigrid.h"
#include "snapshot/actor_states.h"
#include "step_stats.h"

namespace vp {

using ColliderLookup = std::function<const Collider*(uint32_t index1, uint32_t generation)>;

struct DeformableStepInput {
  double dt = 1.0 / 60.0;
  Vec3 gravity = Vec3::Zero();
  // The solve stops at `deadline` once its residual is at or below the desc's targetResidual
  // (the accuracy floor), and at `floorDeadline` in any case (frame_plan.h).
  Deadline deadline, floorDeadline;
  TaskSystem* tasks = nullptr;
  ColliderLookup collider;  // resolves attachment targets; attachments to vanished colliders are dropped
  std::vector<ContactCollider> colliders;  // what the surface collides with this step
  // When set (3 per node), contacts are detected along this motion instead of the velocity:
  // the static solve's pseudo-steps start at rest but must catch what their step will reach.
  const Array<double>* contactLookahead = nullptr;
  // When > 0, the solver's iteration cap instead of the desc's (a per-frame cap): the static
  // solve, outside any frame, lets CG run to its tolerance.
  int32_t solverMaxIterations = 0;
  // Contacts with other deformables and with itself (deform/pair_contacts.h), found at the
  // frame's start; this body is bodies[pairBody] there.
  const std::vector<PairContact>* pairContacts = nullptr;
  int32_t pairBody = -1;
  // The dynamic rigid bodies those contacts' rigid sides are: pair body rigidBodyBase + r is
  // (*rigidBodies)[r]. When set, the body solves with them: its attachments to them are springs
  // among the pair contacts (attachmentSprings), not held velocities.
  const std::vector<RigidContactBody>* rigidBodies = nullptr;
  int32_t rigidBodyBase = 0;
  const RigidContactBody& rigidBody(int32_t rigidPairBody) const {
    return (*rigidBodies)[static_cast<size_t>(rigidPairBody - rigidBodyBase)];
  }
};

class DeformableBody {
 public:
  static Status create(DeformableDesc desc, std::unique_ptr<DeformableBody>* out);

  // Advances one step; fills stats (phases, iterations, residual, budget cut) and sets
  // stats->diverged if the step blew up (the state is then restored to before the step).
  void step(const DeformableStepInput& input, ActorStats* stats);
  // step() in the stages a contact group runs for each member around its one solve
  // (deform/contact_group_solve.h). beginStep: pins, attachments and contacts prescribe
  // velocities, the system is assembled. finishStep: friction states, x += h v' (restored if it
  // blew up), the render mesh; `solved` holds the group's solved velocities by pair body.
  void beginStep(const DeformableStepInput& input, PhaseTimer& timer);
  void finishStep(const DeformableStepInput& input, bool solveReachedFloor, const PairVelocities& solved,
                  PhaseTimer& timer, ActorStats* stats);
  // A step finished but not kept (a contact group member blew up): back to the state before it.
  void discardStep(TaskSystem& tasks);
  // After an exception out of step() (out of memory): back to the state before the step.
  void abandonStep();

  const DeformableDesc& desc() const { return desc_; }
  void setCollisionFilter(const CollisionFilter& filter) { desc_.filter = filter; }  // from the next step
  ActorSchedule& schedule() { return schedule_; }
  int32_t nodeCount() const { return nodeCount_; }
  int64_t elementCount() const { return static_cast<int64_t>(restVolume_.size()); }
  int degree() const { return degree_; }
  int nodesPerElement() const { return nodesPerElement_; }
  const Array<double>& positions() const { return x_; }  // 3 per node, world frame
  Aabb bounds() const;  // of the nodes
  const Array<double>& velocities() const { return v_; }
  const Array<double>& nodeMasses() const { return mass_; }
  const Array<double>& restPositions() const { return restX_; }  // local frame
  const Array<int32_t>& elementNodes() const { return elementNodes_; }

  Status setVelocities(const double* velocities, int64_t count);  // 3 * nodeCount values
  Status setPositions(const double* positions, int64_t count);    // teleport / reset
  // A new material from the next step (validated; on failure nothing changes): the Lamé
  // parameters and, for degree > 1, the element stiffness matrices are recomputed, and the
  // lumped masses rescaled by the density's ratio (they are linear in it).
  Status setMaterial(const DeformableMaterial& material);
  // The render mesh moved to the current node positions (each step does it; a teleport too).
  void updateRenderMesh(TaskSystem& tasks);
  Status applyForce(int32_t node, const Vec3& force);    // for the next step only
  Status applyImpulse(int32_t node, const Vec3& impulse);  // changes the velocity now
  // An impulse the next step applies to the node (pair contacts' settlement; not validated).
  void addContactImpulse(int32_t node, const Vec3& impulse);
  Status setPinned(const int32_t* nodes, int64_t count, bool pinned);
  bool pinned(int32_t node) const { return pinned_[node] != 0; }
  // Nodes follow the collider rigidly from their current offset in its frame.
  Status attach(const int32_t* nodes, int64_t count, uint32_t colliderIndex1, uint32_t colliderGeneration,
                const Collider& collider);
  void detachAll(uint32_t colliderIndex1, uint32_t colliderGeneration);
  bool attachedTo(int32_t node, uint32_t colliderIndex1, uint32_t colliderGeneration) const;
  // The attachments to the dynamic bodies `rigids` (pair body rigidBase + r) as springs of a
  // contact group's solve (PairContact::attachment) over a step of h: each pulls its node to
  // the point of the body it is attached at, and the body back, so that the attachment pulls
  // both ways. Its step then leaves those nodes free (DeformableStepInput::rigidBodies).
  void attachmentSprings(int32_t pairBody, const std::vector<RigidContactBody>& rigids, int32_t rigidBase,
                         std::vector<PairContact>* out) const;
  int64_t attachmentCount() const { return static_cast<int64_t>(attachments_.size()); }
  // Per node, 1 where the host holds it (pinned or attached), else 0.
  void heldNodes(Array<uint8_t>* out) const;
  const Array<int32_t>& surfaceNodes() const { return surfaceNodes_; }
  // What contact detection between deformables reads of this body, its surface refit to the
  // current positions and to the motion of a step of h (s).
  PairContactBody pairContactBody(double h);
  bool selfCollision() const;  // the desc's switch, Auto resolved
  // Contacts active at the end of the last step (after lift-off releases).
  const Array<NodeContact>& contacts() const { return contacts_.contacts(); }
  // What the last step's contacts with dynamic colliders did to them (empty if it diverged).
  const Array<ContactReaction>& contactReactions() const { return reactions_; }
  // The last step's pair contacts with dynamic rigid bodies that pushed (the spring's normal
  // impulse positive), as node contacts (normal, the collider's point velocity, its handle).
  const Array<NodeContact>& rigidContacts() const { return rigidContacts_; }
  // The body in the fluids (deform/fluid_immersion.h): its surface and its motion as a rigid
  // body's as they see them now, and their loads, which the world sets before each step of
  // the body.
  std::shared_ptr<const PreparedCollider> fluidSurface() { return immersion_.surface(x_, v_); }
  SolidMotion rigidMotion() const { return FluidImmersion::rigidMotion(x_, v_, mass_); }
  FluidImmersion& immersion() { return immersion_; }
  // Before its step: the fluids' loads set in immersion() act on the nodes during it, their
  // viscous drag on the nodes' new velocities.
  void applyFluidLoads(const Vec3& gravity);

  // The render mesh: the desc's, else the tet mesh's boundary; embedded in the tets and
  // moved with them each step. Positions and normals are in the world frame.
  const SurfaceMesh& renderMeshRest() const { return renderMesh_.rest(); }
  const Array<Vec3>& renderPositions() const { return renderMesh_.positions(); }
  const Array<Vec3>& renderNormals() const { return renderMesh_.normals(); }
  // The render surface at its current positions as a BVH, for scene queries.
  const RefitBvh& renderSurfaceBvh() const { return renderMesh_.bvh(); }
  // The tet mesh's dihedral angles and volume against its render surface's, at creation.
  const TetMeshQuality& meshQuality() const { return renderMesh_.quality(); }

  // What evolves from step to step (snapshot/actor_states.h); restoreState takes a state
  // read for this body (its sizes checked) and cannot fail.
  DeformableState saveState() const;
  void restoreState(DeformableState&& state);

  double kineticEnergy() const;
  // Corotated strain energy at the current positions: Σ V (μ ε:ε + λ/2 tr(ε)²) for linear
  // elements, Σ ½ uᵀ K_e u with u = Rᵀ x − x0 for higher degrees (chunked: the same bits for
  // any worker count).
  double elasticEnergy(TaskSystem& tasks) const;
  // Elastic forces at the current positions (3 per node), as the step computes them.
  void elasticForces(TaskSystem& tasks, Array<double>* out);
  // From the next step, the implicit solve runs on the CUDA device (true) or on the CPU. Fails,
  // leaving the solve on the CPU, where no device can be used; a device failure during a step
  // moves the solve back to the CPU for good (logged).
  Status setSolveOnDevice(bool onDevice);
  bool solvesOnDevice() const { return deviceSolve_ != nullptr; }
  // The assembled step matrix of the last step (tests inspect its symmetry).
  const BlockSparseMatrix<double>& stepMatrix() const { return matrix_; }
  // Which preconditioner the solve uses (Auto resolved).
  Preconditioner preconditioner() const;
  const Array<double>& restVolumes() const { return restVolume_; }
  // Degree > 1: the 16 rotated gradient pairs per element of the last assembly, with its
  // stiffness scale (deform/bb_rotated_stiffness.h); p-multigrid's re-discretized levels are
  // assembled from them (deform/degree_level_assembly.h).
  const Array<double>& elementGradientPairs() const { return gradientPairs_; }
  // The mesh and the step matrix's pattern as a device assembly reads them
  // (gpu_kernels/device_element_assembly.h), and the elements' rotations (w, x, y, z).
  gpu::ElementAssemblyView elementAssemblyView() const;
  const Array<double>& elementRotations() const { return rotations_; }

 private:
  // x and v back to the step's start; rotations to identity.
  void restoreStepStart();
  // keptRotation non-null: the element's rotation at the current positions is written there.
  double elementElasticEnergy(int64_t element, double* keptRotation = nullptr) const;
  void energyRotation(int64_t element, const double F[9], double R[9], double* keptRotation) const;
  // elasticEnergy, keeping each element's rotation at the current positions as the warm start
  // of the next corotation (at the end of a step: the next step corotates at these positions).
  double elasticEnergyKeepingRotations(TaskSystem& tasks);
  // The energies and works of the step just solved (vNext_), all but the elastic energy at
  // its end (core/step_energy.h).
  StepEnergy solvedStepEnergy(TaskSystem& tasks, double h, const Vec3& gravity, const std::vector<PairContact>* pairs,
                              int32_t pairBody, const PairVelocities& solved);
  // The guard after integrating: true when the step blew up (not finite, too fast, or an
  // energy gain its work does not explain while its solve reached the accuracy floor).
  bool stepBlewUp(TaskSystem& tasks, StepEnergy energy, bool solveReachedFloor);
  friend class ContactGroupSolve;  // solves the members' step systems as one
  DeformableBody() = default;
  // The stages of create(), after degree_ and the material's Lamé parameters: the nodes
  // numbered and placed at the desc's pose and velocity; the elements' rest gradients, volumes,
  // lumped masses and rotations; the step system's pattern, preconditioner and buffers; the
  // surfaces (contact nodes, the fluids' and other deformables' views, the render mesh).
  Status placeNodes(const DeformableDesc& desc);
  Status measureElements(const DeformableDesc& desc);
  Status buildStepSystem(const DeformableDesc& desc);
  Status buildSurfaces(const DeformableDesc& desc);
  void corotateAndAssemble(TaskSystem& tasks, double stiffnessScale);
  void corotateAndAssembleBB(TaskSystem& tasks, double stiffnessScale);  // degree 2, 3
  template <class AddBlock>
  void gatherRows(TaskSystem& tasks, int64_t grain, const AddBlock& addBlock);
  // Parts of beginStep and finishStep. holdNodes: pins, attachments and contacts prescribe
  // velocities (held_, vNext_). assembleStepSystem: the mass and the right-hand side on top of
  // the corotated stiffness. integrateAndGuard: x += h v', restored if it blew up.
  void holdNodes(const DeformableStepInput& in);
  void assembleStepSystem(const DeformableStepInput& in);
  // Whether a node is pinned or attached (deform/rotating_position_update.h).
  bool pinnedOrAttached() const;
  void integrateAndGuard(const DeformableStepInput& in, bool solveReachedFloor, const PairVelocities& solved,
                         ActorStats* stats);
  // Scalar k of the coupled pair contacts' terms between different nodes at the solved
  // velocities (0 outside a coupled solve): part of A v' at a node, for its impulses.
  double pairCouplingAt(size_t k) const { return pair_.coupling.empty() ? 0.0 : pair_.coupling[k]; }
  // After the solve: what the step's contacts did to dynamic colliders (reactions_), the collider
  // contacts' and the coupled pair contacts' with rigid bodies (`solved` as finishStep's).
  void recordReactions(TaskSystem& tasks, const DeformableStepInput& in, const PairVelocities& solved);
  double massScale(double h) const;  // 1 + h α: Rayleigh's mass damping on the mass term
  // One CG solve of the step system from vNext_, on the device when it has one.
  CgResult solveLinearSystem(const DeformableStepInput& in, const LinearSystem& system, const CgSettings& settings,
                             double massScale);
  // After the matrix or the constraints changed (deform/step_preconditioner.h).
  void refreshPreconditioner(TaskSystem& tasks, double massScale);
  // The preconditioner for a step of h (StepPreconditioner::chooseForStep); block-Jacobi on the device.
  void choosePreconditioner(double h);
  // Node spacings an elastic pressure wave crosses in a step of h, as the step system sees it:
  // sqrt((h² + h β) / (1 + h α)) c_p / spacing (Rayleigh's α and β as assembleStepSystem's).
  double elasticWaveCrossings(double h) const;
  // Constraint impulse of each contact from the solved velocities: A v' − b at its node.
  void contactImpulses(TaskSystem& tasks, Array<Vec3>* impulses);
  Status checkNode(const char* what, int32_t node) const;

  struct Attachment {
    int32_t node;
    uint32_t index1, generation;
    Vec3 localOffset;
  };

  DeformableDesc desc_;
  ActorSchedule schedule_;  // the frame plan's state of this body
  int32_t nodeCount_ = 0;
  double lambda_ = 0.0, mu_ = 0.0;
  Array<double> restX_, x_, v_, mass_, externalForce_;
  // Per node and axis, the fluids' viscous drag its next step solves implicitly (applyFluidLoads).
  Array<double> fluidDrag_;
  double totalMass_ = 0.0;
  double nodeSpacing_ = 0.0;  // the elements' mean edge over the degree, at rest
  double elasticEnergyAtX_ = -1.0;  // elasticEnergy() at x_; < 0: not known (x_ or the material changed)
  int degree_ = 1;
  int nodesPerElement_ = 4;
  Array<int32_t> elementNodes_;     // nodesPerElement_ per element, BB local order
  // Per node: the global vertices an edge/face control point lies on (-1: unused; all -1 for
  // vertex nodes).
  Array<std::array<int32_t, 3>> nodeSupport_;
  Array<double> gradientPairs_;     // degree > 1: 16 rotated 3x3 gradient pairs per element, this step
  BBStiffnessTerms stiffnessTerms_;
  BBStiffnessStructure stiffnessStructure_;  // degree > 1: applies the rest K_e unstored
  Array<double> restGradients_;     // 12 per element
  Array<double> restVolume_;
  Array<double> rotations_;         // 4 per element, quaternion (w,x,y,z) warm start
  Array<uint8_t> pinned_;
  std::vector<Attachment> attachments_;
  ElementIncidence incidence_;      // (element, corner) pairs touching each node
  Array<double> elementForce_;      // 3 * nodesPerElement per element, this step
  Array<double> rotatedGradients_;  // 12 per element, this step
  BlockSparseMatrix<double> matrix_;
  Array<int32_t> scatter_;          // 16 block indices per element
  EmbeddedRenderMesh renderMesh_;
  // Per-step scratch kept to avoid allocation in the hot path.
  Array<double> force_, rhs_, vNext_, backupX_, backupV_;
  NodeConstraints held_;        // what the solve prescribes at each node this step
  Array<int32_t> surfaceNodes_;
  ContactActiveSet contacts_;
  Array<ContactReaction> reactions_;
  Array<NodeContact> rigidContacts_;
  FluidImmersion immersion_;
  double contactMargin_ = 0.0;
  // Its contacts with other deformables, itself and dynamic rigid bodies (pair_contacts.h).
  struct PairContactState {
    ContactSurface surface;                // what other deformables and the body itself touch
    Array<PairFriction> friction;          // per node, its pair contact's friction state
    Array<CornerFriction> cornerFriction;  // of the rigid corners on its triangles
    Array<double> pendingImpulse;          // 3 per node, for the next step (addContactImpulse)
    double depth = 0.0;                    // kPairContactDepthEdges mean edges
    Array<double> coupling;  // 3 per node in a coupled solve, else empty (pairCouplingAt)
  } pair_;
  bool stepBegun_ = false;               // between beginStep's backups and finishStep's end
  CgWorkspace cg_;
  StepPreconditioner preconditioner_;
  std::unique_ptr<DeviceStepSolve> deviceSolve_;  // set: the solve runs on the CUDA device
};

}  // namespace vp
