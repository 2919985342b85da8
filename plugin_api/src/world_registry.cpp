#include "world_registry.h"

#include <mutex>

namespace vp::capi {
namespace {

struct Registry {
  std::mutex mutex;
  SlotMap<World> worlds;
  Registry() { worlds.setGenerationLimit(0x10000); }  // vpWorldId.generation is 16 bits
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

Status registerWorld(std::unique_ptr<World> world, vpWorldId* out) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (r.worlds.capacity() >= 0xFFFF && r.worlds.size() == r.worlds.capacity())
    return fail(Status::OutOfMemory, "too many worlds: at most 65535 may exist at once");
  auto h = r.worlds.insert(std::move(world));
  *out = vpWorldId{static_cast<uint16_t>(h.index1), static_cast<uint16_t>(h.generation)};
  return Status::Ok;
}

Status unregisterWorld(vpWorldId id) {
  Registry& r = registry();
  std::unique_ptr<World> doomed;
  {
    std::lock_guard<std::mutex> lock(r.mutex);
    World* w = r.worlds.get(id.index1, id.generation);
    if (!w) return fail(Status::InvalidId, "world id (%u, %u) is stale or null", id.index1, id.generation);
    if (w->stepping()) return fail(Status::Busy, "world id (%u, %u) is stepping on another thread", id.index1, id.generation);
    doomed = r.worlds.remove(id.index1, id.generation);
  }
  // Destroyed outside the lock: joining its worker threads can take a moment.
  doomed.reset();
  return Status::Ok;
}

size_t liveWorldCount() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.worlds.size();
}

Status resolveWorld(vpWorldId id, World** out) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  World* w = r.worlds.get(id.index1, id.generation);
  if (!w) return fail(Status::InvalidId, "world id (%u, %u) is stale or null", id.index1, id.generation);
  if (w->stepping()) return fail(Status::Busy, "world id (%u, %u) is stepping on another thread", id.index1, id.generation);
  *out = w;
  return Status::Ok;
}

Status resolveCollider(vpColliderId id, World** world, Collider** out) {
  if (id.index1 == 0) return fail(Status::InvalidId, "collider id is null");
  Status s = resolveWorld(id.world, world);
  if (!ok(s)) {
    if (s == Status::InvalidId)
      return fail(Status::InvalidId, "collider id (%u, %u) belongs to world (%u, %u), which is stale or null", id.index1,
                  id.generation, id.world.index1, id.world.generation);
    return s;
  }
  Collider* c = (*world)->collider(handleOf(id));
  if (!c) return fail(Status::InvalidId, "collider id (%u, %u) is stale or destroyed", id.index1, id.generation);
  *out = c;
  return Status::Ok;
}

namespace {

// Actor ids carry their world id; both must resolve, and a stale world is named as such.
template <class Id, class Actor, class Lookup>
Status resolveActor(const char* kind, const Id& id, World** world, Actor** out, const Lookup& lookup) {
  if (id.index1 == 0) return fail(Status::InvalidId, "%s id is null", kind);
  Status s = resolveWorld(id.world, world);
  if (!ok(s)) {
    if (s == Status::InvalidId)
      return fail(Status::InvalidId, "%s id (%u, %u) belongs to world (%u, %u), which is stale or null", kind,
                  id.index1, id.generation, id.world.index1, id.world.generation);
    return s;
  }
  Actor* a = lookup(**world);
  if (!a) return fail(Status::InvalidId, "%s id (%u, %u) is stale or destroyed", kind, id.index1, id.generation);
  *out = a;
  return Status::Ok;
}

}  // namespace

Status resolveDeformable(vpDeformableId id, World** world, DeformableBody** out) {
  return resolveActor("deformable", id, world, out, [&](World& w) { return w.deformable(handleOf(id)); });
}

Status resolveFluid(vpFluidId id, World** world, FluidActor** out) {
  return resolveActor("fluid", id, world, out, [&](World& w) { return w.fluid(handleOf(id)); });
}

void fillActorStats(const ActorStats& in, vpActorStats* out) {
  *out = vpActorStats{};
  out->kind = static_cast<vpActorKind>(in.kind);
  out->index1 = in.index1;
  out->totalMs = static_cast<float>(in.totalMs);
  out->diverged = in.diverged ? 1 : 0;
  out->simulatedDt = static_cast<float>(in.simulatedDt);
  out->interval = in.interval;
  out->completedStep = in.completedStep ? 1 : 0;
  out->progress = static_cast<float>(in.progress);
  out->slices = in.slices;
  out->residual = static_cast<float>(in.residual);
  out->priority = in.priority;
  out->floorMissed = in.floorMissed ? 1 : 0;
  static_assert(kPhaseCount == vpPhase_Count && kPhaseCount <= VP_MAX_PHASES, "phase tables must match");
  for (int p = 0; p < kPhaseCount; ++p) {
    const PhaseStats& ph = in.phases[p];
    out->phases[p] = vpPhaseStats{static_cast<float>(ph.ms), ph.iterations, static_cast<float>(ph.residual),
                                  ph.budgetCut ? 1 : 0};
  }
}

}  // namespace vp::capi
