#include "world_registry.h"

#include <atomic>
#include <mutex>

namespace vp::capi {

// The lease is the C ABI function holding the world (nullptr: free), named in Busy errors.
struct WorldEntry {
  std::unique_ptr<World> world;
  std::atomic<const char*> holder{nullptr};
};

namespace {

// vpWorldId's index1 and generation are 16 bits each.
constexpr uint32_t kMaxWorldSlots = 0xFFFF;
constexpr uint32_t kWorldGenerationLimit = 0x10000;

struct Registry {
  std::mutex mutex;
  SlotMap<WorldEntry> worlds;
  Registry() { worlds.setGenerationLimit(kWorldGenerationLimit); }
};

const char* kindName(uint32_t generation) {
  switch (generation >> kIdKindShift) {
    case uint32_t(IdKind::Collider): return "collider";
    case uint32_t(IdKind::Deformable): return "deformable";
    case uint32_t(IdKind::Fluid): return "fluid";
    default: return nullptr;
  }
}

Registry& registry() {
  static Registry r;
  return r;
}

// Under the registry's lock: the entry for id with its lease taken by this call, or an error.
Status acquire(Registry& r, vpWorldId id, WorldEntry** out) {
  WorldEntry* e = r.worlds.get(id.index1, id.generation);
  if (!e) return fail(Status::InvalidId, "world id (%u, %u) is stale or null", id.index1, id.generation);
  const char* expected = nullptr;
  const char* self = currentCall() ? currentCall() : "a VolPhys call";
  if (!e->holder.compare_exchange_strong(expected, self, std::memory_order_acquire))
    return fail(Status::Busy, "world id (%u, %u) is in use by %s, which has not returned (calls on one world must not overlap)",
                id.index1, id.generation, expected);
  *out = e;
  return Status::Ok;
}

}  // namespace

WorldLease::~WorldLease() {
  if (entry_) entry_->holder.store(nullptr, std::memory_order_release);
}
World* WorldLease::operator->() const { return entry_->world.get(); }
World& WorldLease::operator*() const { return *entry_->world; }

Status registerWorld(std::unique_ptr<World> world, vpWorldId* out) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.worlds.canInsert(kMaxWorldSlots))
    return fail(Status::OutOfMemory,
                "no world id left: at most %u worlds exist at once, and each id slot retires after %u worlds",
                kMaxWorldSlots, kWorldGenerationLimit - 1);
  auto entry = std::make_unique<WorldEntry>();
  entry->world = std::move(world);
  auto h = r.worlds.insert(std::move(entry));
  *out = vpWorldId{static_cast<uint16_t>(h.index1), static_cast<uint16_t>(h.generation)};
  return Status::Ok;
}

Status unregisterWorld(vpWorldId id) {
  Registry& r = registry();
  std::unique_ptr<WorldEntry> doomed;
  {
    std::lock_guard<std::mutex> lock(r.mutex);
    WorldEntry* e;
    VP_TRY(acquire(r, id, &e));
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

Status resolveWorld(vpWorldId id, WorldLease* out) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  return acquire(r, id, &out->entry_);
}

Status checkIdKind(const char* expectedName, IdKind expected, uint32_t index1, uint32_t generation) {
  if (generation >> kIdKindShift == static_cast<uint32_t>(expected)) return Status::Ok;
  if (const char* actual = kindName(generation))
    return fail(Status::InvalidId, "%s id (%u, %u) is a %s id", expectedName, index1, generation, actual);
  return fail(Status::InvalidId, "%s id (%u, %u) is not an id VolPhys issued (no kind in its generation)",
              expectedName, index1, generation);
}

Status resolveCollider(vpColliderId id, WorldLease* world, Collider** out) {
  if (id.index1 == 0) return fail(Status::InvalidId, "collider id is null");
  VP_TRY(checkIdKind("collider", IdKind::Collider, id.index1, id.generation));
  Status s = resolveWorld(id.world, world);
  if (!ok(s)) {
    if (s == Status::InvalidId)
      return fail(Status::InvalidId, "collider id (%u, %u) belongs to world (%u, %u), which is stale or null", id.index1,
                  id.generation, id.world.index1, id.world.generation);
    return s;
  }
  return resolveColliderIn(id.world, **world, id, out);
}

Status resolveColliderIn(vpWorldId world, World& w, vpColliderId id, Collider** out) {
  if (id.index1 == 0) return fail(Status::InvalidId, "collider id is null");
  VP_TRY(checkIdKind("collider", IdKind::Collider, id.index1, id.generation));
  if (id.world.index1 != world.index1 || id.world.generation != world.generation)
    return fail(Status::InvalidId, "collider id (%u, %u) belongs to world (%u, %u), not to world (%u, %u)", id.index1,
                id.generation, id.world.index1, id.world.generation, world.index1, world.generation);
  Collider* c = w.collider(handleOf(id));
  if (!c) return fail(Status::InvalidId, "collider id (%u, %u) is stale or destroyed", id.index1, id.generation);
  *out = c;
  return Status::Ok;
}

namespace {

// Actor ids carry their world id; both must resolve, and a stale world is named as such.
template <class Id, class Actor, class Lookup>
Status resolveActor(const char* kind, IdKind idKind, const Id& id, WorldLease* world, Actor** out,
                    const Lookup& lookup) {
  if (id.index1 == 0) return fail(Status::InvalidId, "%s id is null", kind);
  VP_TRY(checkIdKind(kind, idKind, id.index1, id.generation));
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

Status resolveDeformable(vpDeformableId id, WorldLease* world, DeformableBody** out) {
  return resolveActor("deformable", IdKind::Deformable, id, world, out, [&](World& w) { return w.deformable(handleOf(id)); });
}

Status resolveFluid(vpFluidId id, WorldLease* world, FluidActor** out) {
  return resolveActor("fluid", IdKind::Fluid, id, world, out, [&](World& w) { return w.fluid(handleOf(id)); });
}

void fillActorStats(const ActorStats& in, vpActorStats* out) {
  *out = vpDefaultActorStats();
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
  out->device = in.onDevice ? vpDevice_Cuda : vpDevice_Cpu;
  static_assert(kPhaseCount == vpPhase_Count && kPhaseCount <= VP_MAX_PHASES, "phase tables must match");
  for (int p = 0; p < kPhaseCount; ++p) {
    const PhaseStats& ph = in.phases[p];
    out->phases[p] = vpPhaseStats{static_cast<float>(ph.ms), ph.iterations, static_cast<float>(ph.residual),
                                  ph.budgetCut ? 1 : 0};
    if (ph.failed) out->failedPhases |= 1u << p;
  }
}

}  // namespace vp::capi
