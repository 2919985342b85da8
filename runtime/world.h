// A VolPhys world: rigid colliders (Bullet), deformable and fluid actors, stepped
// together under one per-frame budget. Owned by the C ABI's world registry.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "collide/collider.h"
#include "collide/collision_world.h"
#include "contact_events.h"
#include "core/budget_clock.h"
#include "core/slot_map.h"
#include "core/task_system.h"
#include "core/worker_contention.h"
#include "deform/deformable_body.h"
#include "deform/static_equilibrium.h"
#include "fluid/fluid_actor.h"
#include "frame_plan.h"
#include "step_stats.h"

namespace vp {

// Where the deformables' implicit solves run (vpDevice; deform/device_step_solve.h).
enum class ComputeDevice : int { Auto = 0, Cpu = 1, Cuda = 2 };

struct WorldConfig {
  Vec3 gravity{0.0, -9.81, 0.0};
  int workerCount = 1;
  double frameBudgetMs = 16.0;
  double rigidMaxSubstep = 1.0 / 120.0;
  TaskHooks tasks;
  Clock clock;
  void* userData = nullptr;
  ComputeDevice device = ComputeDevice::Cpu;
};

// Messages name the vpWorldDef field.
Status validateWorldConfig(const WorldConfig& config);
Status validateFrameBudget(double frameBudgetMs);
Status validateGravity(const Vec3& gravity);

// A solid as an actor's stage sees it, with the filter it meets actors by.
template <class Entry>
struct Filtered {
  CollisionFilter filter;
  Entry entry;
};

using ColliderHandle = SlotMap<Collider>::Handle;
using DeformableHandle = SlotMap<DeformableBody>::Handle;
using FluidHandle = SlotMap<FluidActor>::Handle;

class World {
 public:
  // Handle generations stay below this: the C ABI keeps the two bits above for the id's kind.
  static constexpr uint32_t kHandleGenerationLimit = 1u << 30;

  static Status create(const WorldConfig& config, std::unique_ptr<World>* out);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  Status step(double dt);

  // Everything that evolves, as bytes (snapshot/state_stream.h has the format; world_state.cpp
  // the contents). Saving first completes any fluid step in progress (its remaining slices run
  // here) and rebuilds Bullet's caches from the state (CollisionWorld::rebuild), as a restore
  // does: stepping after a restore is then bitwise the stepping after the save. A world that
  // saves can therefore differ in the last bits from one that does not.
  Status saveState(std::vector<uint8_t>* out);
  // Reads the whole buffer before it changes anything: a buffer that is truncated, corrupted,
  // of another format or saved from a world with other actors (ids, kinds, sizes) is refused
  // with the reason and the world stays as it was.
  Status restoreState(const uint8_t* data, size_t size);
  const StepStats& lastStats() const { return stats_; }
  // Deformable-collider contacts that began or ended in the last step (contact_events.h).
  const std::vector<ContactEvent>& contactEvents() const { return contactEvents_.events(); }

  // Validates (and may load a mesh file); on failure nothing changes.
  Status createCollider(ColliderDesc desc, ColliderHandle* out);
  Status destroyCollider(ColliderHandle handle);
  Collider* collider(ColliderHandle handle) const { return colliders_.get(handle.index1, handle.generation); }
  std::vector<ColliderHandle> colliderHandles() const;  // slot order
  size_t colliderCount() const { return colliders_.size(); }
  bool findCollider(const std::string& name, ColliderHandle* out) const;
  bool colliderHandleOf(const Collider* collider, ColliderHandle* out) const;
  CollisionWorld& collisionWorld() { return collision_; }  // scene queries read Bullet's world

  Status createDeformable(DeformableDesc desc, DeformableHandle* out);
  Status destroyDeformable(DeformableHandle handle);
  DeformableBody* deformable(DeformableHandle h) const { return deformables_.get(h.index1, h.generation); }
  std::vector<DeformableHandle> deformableHandles() const;
  size_t deformableCount() const { return deformables_.size(); }
  bool findDeformable(const std::string& name, DeformableHandle* out) const;
  // The deformable's static equilibrium against the world as it stands (deform/static_equilibrium.h).
  Status solveDeformableStatic(DeformableHandle handle, int32_t maxIterations, double tolerance,
                               StaticSolveResult* result);

  Status createFluid(FluidDesc desc, FluidHandle* out);
  Status destroyFluid(FluidHandle handle);
  FluidActor* fluid(FluidHandle h) const { return fluids_.get(h.index1, h.generation); }
  std::vector<FluidHandle> fluidHandles() const;
  size_t fluidCount() const { return fluids_.size(); }
  bool findFluid(const std::string& name, FluidHandle* out) const;

  // Filters (core/collision_filter.h) take effect from the next step; every value is valid.
  void setColliderFilter(Collider& collider, const CollisionFilter& filter) { collision_.setFilter(collider, filter); }
  Status setGravity(const Vec3& gravity);
  const Vec3& gravity() const { return config_.gravity; }
  Status setFrameBudget(double frameBudgetMs);
  const WorldConfig& config() const { return config_; }
  TaskSystem& tasks() { return *tasks_; }

 private:
  explicit World(const WorldConfig& config);
  // The stages of a step (frame_plan.h has the policy): the rigid bodies here, the
  // deformables in world_deformables.cpp, the fluids in world_fluids.cpp.
  void stepRigidBodies(double dt, const Deadline& frame, StepStats* stats);
  // Returns whether every deformable that stepped reached its accuracy floor.
  bool stepDeformables(double dt, const Deadline& frame, StepStats* stats);
  void stepFluids(double dt, const Deadline& frame, bool floorsHeld, StepStats* stats);
  void finishStats(const Deadline& frame, StepStats* stats);
  // The loads the rigid bodies take in this step, set on them: the host's, the deformables'
  // pushes of the last frame, each fluid's from its last completed step and each liquid's
  // weight where the body is now. Returns the bodies loaded, once each.
  std::vector<Collider*> prepareRigidLoads(double dt);

  // The deformables' stage, in the order it runs.
  struct DeformableFrame;  // the deformables of one frame as planned
  DeformableFrame planDeformables(double dt, const Deadline& frame, uint64_t stepIndex);
  // `planned` with its pacing under a budget (FramePlan::Pacing): every frame when it can meet
  // a dynamic rigid body within `lookahead` seconds (rigidReach: where they can go), else with
  // the two-way liquids that weigh on it.
  FramePlan::Deformable pacedDeformable(FramePlan::Deformable planned, const DeformableBody& body,
                                        const std::vector<Filtered<Aabb>>& rigidReach, double lookahead) const;
  // The deformables' contacts of a frame, found once at its start for all their steps: which
  // bodies solve with the dynamic rigid bodies they touch, those bodies, the pair contacts
  // (attachment springs included) and the groups that solve together (deform/contact_groups.h).
  struct FrameContacts {
    std::vector<bool> touchesRigid;  // by handle
    std::vector<RigidContactBody> rigids;
    std::vector<PairContact> pairs;
    std::vector<std::vector<int>> groups;
  };
  FrameContacts findFrameContacts(const DeformableFrame& d, double dt, const Deadline& frame, StepStats* stats);
  void stepContactGroups(DeformableFrame& d, const FrameContacts& contacts, const Deadline& frame);
  // One group's step within `deadlines`: its members' inputs, the fluids' loads on them, the
  // step, and its time shared out among them.
  void stepGroupWithin(DeformableFrame& d, const std::vector<int>& members, const FrameContacts& contacts,
                       const std::vector<Filtered<ContactCollider>>& colliders,
                       const FramePlan::DeformableDeadlines& deadlines, const Deadline& frame);
  // One step of a contact group's members (deform/contact_groups.h; a lone body alone), indices
  // into the frame's handles; inputs by member.
  void stepGroup(DeformableFrame& d, const std::vector<int>& members, const std::vector<DeformableStepInput>& inputs);
  // The plan's bookkeeping of the bodies that stepped (and waited); returns by handle whether
  // each missed its floor.
  std::vector<bool> finishDeformableSteps(DeformableFrame& d, const Deadline& frame, StepStats* stats);

  // What the deformables' stage reads.
  // Body handles[i]'s step input in this frame, bar its deadlines.
  DeformableStepInput frameStepInput(const std::vector<DeformableHandle>& handles, int i,
                                     const std::vector<Filtered<ContactCollider>>& colliders,
                                     const FrameContacts& contacts) const;
  // The deformables' contacts with each other and themselves at the frame's start, found once
  // for all their steps (each reads the others as they were then: the same for any worker count),
  // and, for those whose touchesRigid is set, with the dynamic rigid bodies `rigids`.
  std::vector<PairContact> findDeformablePairContacts(const std::vector<DeformableHandle>& handles,
                                                      const std::vector<bool>& touchesRigid,
                                                      const std::vector<RigidContactBody>& rigids, double dt,
                                                      const Deadline& frame, StepStats* stats);
  // The attachments of the bodies that touch rigid ones to those (DeformableBody::attachmentSprings),
  // added to the pair contacts; a node's contact with the body it is attached to is dropped.
  void addAttachmentSprings(const std::vector<DeformableHandle>& handles, const std::vector<bool>& touchesRigid,
                            const std::vector<RigidContactBody>& rigids, std::vector<PairContact>* pairs) const;
  // The dynamic bodies a deformable's step can solve with it (deform/contact_group_solve.h).
  std::vector<RigidContactBody> rigidContactBodies() const;
  // The boxes the dynamic rigid bodies can reach within `lookahead` seconds, with their filters.
  std::vector<Filtered<Aabb>> dynamicBodiesReach(double lookahead) const;
  // Deformables push back: each contact reaction of the body's last step acts on its dynamic
  // collider as an impulse (equal and opposite to the one on the node), applied when the next
  // rigid step begins (Collider::addContactImpulse).
  void pushDynamicColliders(const DeformableBody& body);
  // A deformable's step input without its time step and deadlines: gravity, the pool, the
  // colliders its filter meets and the lookup of its attachments' colliders.
  template <class FilteredColliders>
  DeformableStepInput deformableStepInput(const DeformableBody& body, const FilteredColliders& colliders) const;

  // The fluids' stage, in the order it runs.
  struct FluidFrame;  // the fluids of one frame as planned
  // What the fluids see as solids: the colliders with exact geometry and the surfaces of the
  // deformables that reach into some fluid's domain (deform/fluid_immersion.h).
  std::vector<Filtered<FluidCollider>> fluidSolids(const Deadline& frame, StepStats* stats);
  FluidFrame planFluids(double dt, const Deadline& frame, bool floorsHeld, double budgetMs);
  void advanceFluids(FluidFrame& f, const std::vector<Filtered<FluidCollider>>& solids, const Deadline& frame);
  // The plan's bookkeeping of the fluids that ran.
  void finishFluidSteps(FluidFrame& f, const Deadline& frame, bool floorsHeld, StepStats* stats);
  // A fluid step that completed: the plan's bookkeeping of its rate and cost.
  static void noteFluidStepCompleted(ActorSchedule& s);
  // The fluids' loads on a deformable, from their last completed steps, set before its step.
  void setFluidLoads(DeformableHandle handle, DeformableBody& body) const;
  // What the fluids of at least `priority` are expected to need this frame.
  double fluidsExpectedMs(int priority);
  // Runs the rest of every fluid step in progress (for a saved state).
  Status completeFluidSteps();

  std::vector<Collider*> collidersInSlotOrder() const;
  // Actors that do not depend on each other in a stage run side by side on the worker pool
  // (world_stages.h), each its own parallel loops inline, when there are at least two and no
  // more than workers.
  bool runsConcurrently(int actors) const;
  // The built-in pool's workers go off while other work keeps the cores busy
  // (core/worker_contention.h); the run delay is that of the pool's threads and the caller.
  double poolRunDelayMs() const;
  void balanceWorkers(const Deadline& frame, double runDelayAtStart);
  ActorStats actorStats(ActorKind kind, uint32_t index1, uint32_t generation, int priority, double dt) const;

  WorldConfig config_;
  std::unique_ptr<TaskSystem> tasks_;
  WorkerContention contention_;
  CollisionWorld collision_;
  const bool deformablesOnDevice_;  // config_.device resolved: new deformables solve on the CUDA device
  SlotMap<Collider> colliders_;
  SlotMap<DeformableBody> deformables_;
  SlotMap<FluidActor> fluids_;
  StepStats stats_;
  ContactEventTracker contactEvents_;
  // Set when an actor's step ran out of memory and was undone (actors may run side by side).
  std::atomic<bool> actorOutOfMemory_{false};
};

}  // namespace vp
