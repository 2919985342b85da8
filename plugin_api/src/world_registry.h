// The process-wide table of worlds behind vpWorldId, and the id <-> object translation every
// shim uses. Ids from a destroyed world never resolve: the world slot's generation changes,
// and child ids carry their world id.
#pragma once

#include <memory>

#include "capi_convert.h"
#include "world.h"

namespace vp::capi {

Status registerWorld(std::unique_ptr<World> world, vpWorldId* out);
Status unregisterWorld(vpWorldId id);  // fails with Busy while it steps
size_t liveWorldCount();

// Resolve for an ordinary call: InvalidId if stale/null, Busy if stepping on another thread.
Status resolveWorld(vpWorldId id, World** out);
Status resolveCollider(vpColliderId id, World** world, Collider** out);

Status resolveDeformable(vpDeformableId id, World** world, DeformableBody** out);
Status resolveFluid(vpFluidId id, World** world, FluidActor** out);

inline vpColliderId makeColliderId(vpWorldId world, ColliderHandle h) { return vpColliderId{h.index1, h.generation, world}; }
inline ColliderHandle handleOf(vpColliderId id) { return ColliderHandle{id.index1, id.generation}; }
inline vpDeformableId makeDeformableId(vpWorldId world, DeformableHandle h) {
  return vpDeformableId{h.index1, h.generation, world};
}
inline DeformableHandle handleOf(vpDeformableId id) { return DeformableHandle{id.index1, id.generation}; }
inline vpFluidId makeFluidId(vpWorldId world, FluidHandle h) { return vpFluidId{h.index1, h.generation, world}; }
inline FluidHandle handleOf(vpFluidId id) { return FluidHandle{id.index1, id.generation}; }

void fillActorStats(const ActorStats& in, vpActorStats* out);

}  // namespace vp::capi
