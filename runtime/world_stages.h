// What the world's stages (world.cpp, world_deformables.cpp, world_fluids.cpp) share.
#pragma once

#include <vector>

#include "core/parallel_for.h"
#include "world.h"

namespace vp {

// Whether a fluid reaches a body within `bounds` and sees it (it then takes it as a solid).
inline bool reaches(const FluidActor& fluid, const Aabb& bounds, const CollisionFilter& filter) {
  return fluid.domainBounds().overlaps(bounds) && fluid.desc().filter.meets(filter);
}

// Whether a liquid's weight acts on such a body: a two-way liquid that reaches it.
inline bool weighsOn(const FluidActor& fluid, const Aabb& bounds, const CollisionFilter& filter) {
  return fluid.desc().kind == FluidKind::Liquid && fluid.desc().twoWayCoupling && reaches(fluid, bounds, filter);
}

// The colliders an actor with `filter` meets, in the list's order.
template <class Entry>
std::vector<Entry> meeting(const std::vector<Filtered<Entry>>& colliders, const CollisionFilter& filter) {
  std::vector<Entry> out;
  out.reserve(colliders.size());
  for (const Filtered<Entry>& c : colliders)
    if (c.filter.meets(filter)) out.push_back(c.entry);
  return out;
}

// work(n) for n in [0, count): in turn, or side by side on the pool (World::runsConcurrently),
// one actor per item; the pool runs each actor's own parallel loops inline (task_system.h).
template <class Work>
void runActors(TaskSystem& tasks, bool concurrent, int count, const Work& work) {
  if (!concurrent) {
    for (int n = 0; n < count; ++n) work(n);
    return;
  }
  parallelFor(tasks, count, 1, [&](int64_t begin, int64_t end) {
    for (int64_t n = begin; n < end; ++n) work(static_cast<int>(n));
  });
}

}  // namespace vp
