// The process-wide table of worlds behind vpWorldId, and the id <-> object translation every
// shim uses. Ids from a destroyed world never resolve: the world slot's generation changes,
// and child ids carry their world id.
//
// Calls on one world must not overlap (volphys.h, threading contract); the registry enforces
// it rather than trusting the host. Every call on a world holds that world's lease for its
// whole length: taking it is one compare-and-swap on the world's entry, done under the
// registry's lock together with the id lookup, so a second call that overlaps (a host bug:
// two threads stepping one world, a getter during a step, a destroy racing a step) gets Busy
// and changes nothing. Destroy takes the lease too, so a world is never freed under a call.
#pragma once

#include <memory>

#include "capi_convert.h"
#include "world.h"

namespace vp::capi {

struct WorldEntry;

// Exclusive use of one world until it goes out of scope (including by an exception).
class WorldLease {
 public:
  WorldLease() = default;
  ~WorldLease();
  WorldLease(const WorldLease&) = delete;
  WorldLease& operator=(const WorldLease&) = delete;

  World* operator->() const;
  World& operator*() const;

 private:
  friend Status resolveWorld(vpWorldId id, WorldLease* out);
  WorldEntry* entry_ = nullptr;
};

Status registerWorld(std::unique_ptr<World> world, vpWorldId* out);
Status unregisterWorld(vpWorldId id);  // Busy while another call holds the world
size_t liveWorldCount();

// Resolve for an ordinary call: InvalidId if stale/null, Busy if another call holds the world.
Status resolveWorld(vpWorldId id, WorldLease* out);
Status resolveCollider(vpColliderId id, WorldLease* world, Collider** out);
// A collider of a world this call already holds (InvalidId if it is another world's).
Status resolveColliderIn(vpWorldId world, World& w, vpColliderId id, Collider** out);

Status resolveDeformable(vpDeformableId id, WorldLease* world, DeformableBody** out);
Status resolveFluid(vpFluidId id, WorldLease* world, FluidActor** out);

// Child ids carry their kind in the generation's bits at and above kIdKindShift, so an id of
// one kind passed as another (a C host can reinterpret the structs) never resolves; the
// world's handles keep their generations below (World::kHandleGenerationLimit).
enum class IdKind : uint32_t { Collider = 1, Deformable = 2, Fluid = 3 };
constexpr uint32_t kIdKindShift = 30;
static_assert(World::kHandleGenerationLimit == 1u << kIdKindShift, "handle generations must leave the kind bits free");
inline uint32_t taggedGeneration(IdKind kind, uint32_t generation) {
  return static_cast<uint32_t>(kind) << kIdKindShift | generation;
}
inline uint32_t untaggedGeneration(uint32_t generation) { return generation & (World::kHandleGenerationLimit - 1); }
// InvalidId naming the kind the id is, unless its kind bits say `expected`.
Status checkIdKind(const char* expectedName, IdKind expected, uint32_t index1, uint32_t generation);

inline vpColliderId makeColliderId(vpWorldId world, ColliderHandle h) {
  return vpColliderId{h.index1, taggedGeneration(IdKind::Collider, h.generation), world};
}
inline ColliderHandle handleOf(vpColliderId id) { return ColliderHandle{id.index1, untaggedGeneration(id.generation)}; }
inline vpDeformableId makeDeformableId(vpWorldId world, DeformableHandle h) {
  return vpDeformableId{h.index1, taggedGeneration(IdKind::Deformable, h.generation), world};
}
inline DeformableHandle handleOf(vpDeformableId id) {
  return DeformableHandle{id.index1, untaggedGeneration(id.generation)};
}
inline vpFluidId makeFluidId(vpWorldId world, FluidHandle h) {
  return vpFluidId{h.index1, taggedGeneration(IdKind::Fluid, h.generation), world};
}
inline FluidHandle handleOf(vpFluidId id) { return FluidHandle{id.index1, untaggedGeneration(id.generation)}; }

void fillActorStats(const ActorStats& in, vpActorStats* out);

}  // namespace vp::capi
