// World lifetime, stepping, scenes and statistics.
#include <type_traits>

#include "capi_convert.h"
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
  return def;
}

vpStatus vpWorldCreate(const vpWorldDef* def, vpWorldId* outWorld) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(def);
    VP_REQUIRE_POINTER(outWorld);
    VP_TRY(checkStructSize("vpWorldDef", def->structSize, sizeof(vpWorldDef)));
    VP_TRY(checkVec3("gravity", def->gravity));
    WorldConfig config;
    config.gravity = toVec3(def->gravity);
    config.workerCount = def->workerCount;
    config.frameBudgetMs = def->frameBudgetMs;
    config.rigidMaxSubstep = def->rigidMaxSubstep;
    static_assert(std::is_same_v<EnqueueTaskFn, vpEnqueueTaskFn*>, "task hook types must match");
    config.tasks.enqueue = def->enqueueTask;
    config.tasks.finish = def->finishTask;
    config.tasks.userContext = def->userTaskContext;
    config.clock.now = def->clock;
    config.clock.context = def->clockContext;
    config.userData = def->userData;
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

vpStatus vpWorldGetStepStats(vpWorldId id, vpStepStats* out) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(out);
    VP_TRY(checkStructSize("vpStepStats", out->structSize, sizeof(vpStepStats)));
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    const StepStats& s = w->lastStats();
    out->stepIndex = s.stepIndex;
    out->dt = static_cast<float>(s.dt);
    out->totalMs = static_cast<float>(s.totalMs);
    out->budgetMs = static_cast<float>(s.budgetMs);
    out->budgetCut = s.budgetCut ? 1 : 0;
    out->actorCount = static_cast<int32_t>(s.actors.size());
    out->colliderCount = s.colliderCount;
    out->rigidSubsteps = s.rigidSubsteps;
    out->fluidInterval = s.fluidInterval;
    out->overBudgetMs = static_cast<float>(s.overBudgetMs);
    out->budgetInfeasible = s.budgetInfeasible ? 1 : 0;
    out->maxSliceMs = static_cast<float>(s.maxSliceMs);
    return Status::Ok;
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
    fillActorStats(s.actors[static_cast<size_t>(actorIndex)], out);
    return Status::Ok;
  });
}

}  // extern "C"
