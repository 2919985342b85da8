// World lifetime, stepping, scenes and statistics.
#include <type_traits>

#include "capi_convert.h"
#include "capi_versioned_struct.h"
#include "scene/scene_loader.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;


extern "C" {

vpWorldDef vpDefaultWorldDef(void) {
  vpWorldDef def{};
  def.structSize = sizeof(vpWorldDef);
  def.gravity = vpVec3{0.0f, -9.81f, 0.0f};
  def.workerCount = 1;
  def.frameBudgetMs = 16.0f;
  def.rigidMaxSubstep = 1.0f / 120.0f;
  def.device = vpDevice_Cpu;
  return def;
}

vpStatus vpWorldCreate(const vpWorldDef* def, vpWorldId* outWorld) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(def);
    VP_REQUIRE_POINTER(outWorld);
    vpWorldDef d;  // the host's def, with an older header's missing fields at their defaults
    VP_TRY(readVersioned("vpWorldDef", def, vpDefaultWorldDef(), &d));
    VP_TRY(checkVec3("gravity", d.gravity));
    WorldConfig config;
    config.gravity = toVec3(d.gravity);
    config.workerCount = d.workerCount;
    config.frameBudgetMs = d.frameBudgetMs;
    config.rigidMaxSubstep = d.rigidMaxSubstep;
    static_assert(std::is_same_v<EnqueueTaskFn, vpEnqueueTaskFn*>, "task hook types must match");
    config.tasks.enqueue = d.enqueueTask;
    config.tasks.finish = d.finishTask;
    config.tasks.userContext = d.userTaskContext;
    config.clock.now = d.clock;
    config.clock.context = d.clockContext;
    config.userData = d.userData;
    config.device = static_cast<ComputeDevice>(d.device);  // validateWorldConfig checks the range
    std::unique_ptr<World> world;
    VP_TRY(World::create(config, &world));
    return registerWorld(std::move(world), outWorld);
  });
}

vpStatus vpWorldDestroy(vpWorldId world) {
  return guarded(__func__, [&] { return unregisterWorld(world); });
}

vpStatus vpWorldIsValid(vpWorldId id) {
  return guarded(__func__, [&] {
    WorldLease w;
    return resolveWorld(id, &w);
  });
}

vpStatus vpWorldSetGravity(vpWorldId id, vpVec3 gravity) {
  return guarded(__func__, [&] {
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    VP_TRY(checkVec3("gravity", gravity));
    return w->setGravity(toVec3(gravity));
  });
}

vpStatus vpWorldGetGravity(vpWorldId id, vpVec3* outGravity) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outGravity);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    *outGravity = toC(w->gravity());
    return Status::Ok;
  });
}

vpStatus vpWorldSetFrameBudget(vpWorldId id, float frameBudgetMs) {
  return guarded(__func__, [&] {
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    return w->setFrameBudget(frameBudgetMs);
  });
}

vpStatus vpWorldStep(vpWorldId id, float dt) {
  return guarded(__func__, [&] {
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    return w->step(dt);
  });
}

vpStatus vpWorldLoadScene(vpWorldId id, const char* path) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(path);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    return loadScene(*w, path);
  });
}

vpStepStats vpDefaultStepStats(void) {
  vpStepStats s{};
  s.structSize = sizeof(vpStepStats);
  return s;
}

vpActorStats vpDefaultActorStats(void) {
  vpActorStats s{};
  s.structSize = sizeof(vpActorStats);
  return s;
}

vpStatus vpWorldGetStepStats(vpWorldId id, vpStepStats* out) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(out);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    const StepStats& s = w->lastStats();
    vpStepStats stats = vpDefaultStepStats();
    stats.stepIndex = s.stepIndex;
    stats.dt = static_cast<float>(s.dt);
    stats.totalMs = static_cast<float>(s.totalMs);
    stats.budgetMs = static_cast<float>(s.budgetMs);
    stats.budgetCut = s.budgetCut ? 1 : 0;
    stats.actorCount = static_cast<int32_t>(s.actors.size());
    stats.colliderCount = s.colliderCount;
    stats.rigidSubsteps = s.rigidSubsteps;
    stats.fluidInterval = s.fluidInterval;
    stats.overBudgetMs = static_cast<float>(s.overBudgetMs);
    stats.budgetInfeasible = s.budgetInfeasible ? 1 : 0;
    stats.maxSliceMs = static_cast<float>(s.maxSliceMs);
    return writeVersioned("vpStepStats", stats, out);
  });
}

vpStatus vpWorldGetActorStats(vpWorldId id, int32_t actorIndex, vpActorStats* out) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(out);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    const StepStats& s = w->lastStats();
    if (actorIndex < 0 || actorIndex >= static_cast<int32_t>(s.actors.size()))
      return fail(Status::InvalidArgument, "actorIndex = %d: must be in [0, %zu)", actorIndex, s.actors.size());
    vpActorStats stats;
    fillActorStats(s.actors[static_cast<size_t>(actorIndex)], &stats);
    return writeVersioned("vpActorStats", stats, out);
  });
}


vpStatus vpWorldGetContactEvents(vpWorldId id, vpContactEvent* outEvents, int32_t capacity, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    if (capacity < 0) return fail(Status::InvalidArgument, "capacity = %d: must be >= 0", capacity);
    if (capacity > 0 && outEvents == nullptr)
      return fail(Status::InvalidArgument, "outEvents is NULL with capacity = %d", capacity);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    const std::vector<ContactEvent>& events = w->contactEvents();
    for (size_t i = 0; i < events.size() && i < static_cast<size_t>(capacity); ++i) {
      const ContactEvent& e = events[i];
      vpContactEvent& out = outEvents[i];
      out = vpContactEvent{};
      out.type = e.type == ContactEvent::Type::Begin ? vpContactEventType_Begin : vpContactEventType_End;
      out.deformable = makeDeformableId(id, DeformableHandle{e.deformableIndex1, e.deformableGeneration});
      out.collider = makeColliderId(id, ColliderHandle{e.colliderIndex1, e.colliderGeneration});
      out.nodeCount = e.nodeCount;
      out.point = toC(e.point);
      out.normal = toC(e.normal);
    }
    *outCount = static_cast<int32_t>(events.size());
    return Status::Ok;
  });
}

}  // extern "C"
