#include <cmath>
#include <cstddef>
#include <cstring>

#include "capi_test_support.h"

namespace {

TEST(CApiWorld, VersionAndHeaderCheck) {
  vpVersion v = vpGetVersion();
  EXPECT_EQ(v.major, VP_VERSION_MAJOR);
  EXPECT_EQ(v.minor, VP_VERSION_MINOR);
  EXPECT_VP_OK(vpCheckVersion());
  EXPECT_EQ(vpCheckHeaderVersion(((VP_VERSION_MAJOR + 1) << 16), sizeof(vpWorldDef)), vpStatus_VersionMismatch);
  EXPECT_TRUE(lastErrorContains("header version"));
  EXPECT_EQ(vpCheckHeaderVersion(VP_HEADER_VERSION, sizeof(vpWorldDef) - 4), vpStatus_VersionMismatch);
  EXPECT_TRUE(lastErrorContains("vpWorldDef.structSize"));
  // 0.x: a header of another minor version may lay the structs out differently.
  if (VP_VERSION_MAJOR == 0) {
    EXPECT_EQ(vpCheckHeaderVersion(VP_HEADER_VERSION - (1u << 8), sizeof(vpWorldDef)), vpStatus_VersionMismatch);
    EXPECT_TRUE(lastErrorContains("header version"));
  }
}

TEST(CApiWorld, CreateStepDestroy) {
  vpWorldDef def = vpDefaultWorldDef();
  vpWorldId world{};
  ASSERT_VP_OK(vpWorldCreate(&def, &world));
  EXPECT_FALSE(vpWorldIdIsNull(world));
  vpColliderDef ground = vpDefaultColliderDef();
  ground.shape.type = vpShapeType_Plane;
  vpColliderId groundId, ballId;
  ASSERT_VP_OK(vpColliderCreate(world, &ground, &groundId));
  vpColliderDef ball = dynamicBall(3.0f);
  ASSERT_VP_OK(vpColliderCreate(world, &ball, &ballId));
  for (int i = 0; i < 180; ++i) ASSERT_VP_OK(vpWorldStep(world, 1.0f / 60.0f));
  vpTransform pose;
  ASSERT_VP_OK(vpColliderGetPose(ballId, &pose));
  EXPECT_NEAR(pose.position.y, 0.5f, 5e-3f);
  vpStepStats stats = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(world, &stats));
  EXPECT_EQ(stats.stepIndex, 180u);
  EXPECT_EQ(stats.colliderCount, 2);
  EXPECT_EQ(stats.actorCount, 1);
  EXPECT_EQ(stats.rigidSubsteps, 2);
  EXPECT_GE(stats.totalMs, 0.0f);
  vpActorStats rigid = vpDefaultActorStats();
  ASSERT_VP_OK(vpWorldGetActorStats(world, 0, &rigid));
  EXPECT_EQ(rigid.kind, vpActorKind_Rigid);
  EXPECT_GE(rigid.phases[vpPhase_Rigid].ms, 0.0f);
  EXPECT_EQ(vpWorldGetActorStats(world, 1, &rigid), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("actorIndex = 1"));
  ASSERT_VP_OK(vpWorldDestroy(world));
  EXPECT_EQ(vpWorldIsValid(world), vpStatus_InvalidId);
}

TEST(CApiWorld, StepWithNothingInIt) {
  ScopedWorld w;
  for (int i = 0; i < 10; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 0.01f));
  vpStepStats stats = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &stats));
  EXPECT_EQ(stats.stepIndex, 10u);
  EXPECT_EQ(stats.colliderCount, 0);
  EXPECT_EQ(stats.budgetCut, 0);
}

// The frame plan's statistics read back through the C structs. Unbudgeted, nothing is over
// the budget or infeasible and every actor steps every frame.
TEST(CApiWorld, StepAndActorStatsCarryTheFramePlanFields) {
  static_assert(offsetof(vpStepStats, overBudgetMs) > offsetof(vpStepStats, fluidInterval),
                "appended after the older fields");
  static_assert(offsetof(vpActorStats, interval) > offsetof(vpActorStats, simulatedDt),
                "appended after the older fields");
  ScopedWorld w;
  vpDeformableDef jelly = vpDefaultDeformableDef();
  jelly.tetFile = VP_TEST_DATA_DIR "/geometry/cube_v41.msh";
  jelly.priority = 7;
  vpDeformableId jellyId{};
  ASSERT_VP_OK(vpDeformableCreate(w.id, &jelly, &jellyId));
  vpFluidDef smoke = vpDefaultFluidDef();
  smoke.resolution[0] = smoke.resolution[1] = smoke.resolution[2] = 8;
  smoke.cellSize = 0.125f;
  smoke.origin = vpVec3{3, 0, 0};
  smoke.priority = -3;
  vpFluidId smokeId{};
  ASSERT_VP_OK(vpFluidCreate(w.id, &smoke, &smokeId));
  for (int i = 0; i < 3; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));

  vpStepStats step = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &step));
  EXPECT_EQ(step.budgetMs, 0.0f);
  EXPECT_EQ(step.overBudgetMs, 0.0f);
  EXPECT_EQ(step.budgetInfeasible, 0);
  EXPECT_GE(step.maxSliceMs, 0.0f);
  EXPECT_LE(step.maxSliceMs, step.totalMs);
  EXPECT_EQ(step.fluidInterval, 1);
  ASSERT_EQ(step.actorCount, 3);  // rigid, the deformable, the fluid

  const int32_t expectedPriority[3] = {0, 7, -3};
  const vpActorKind expectedKind[3] = {vpActorKind_Rigid, vpActorKind_Deformable, vpActorKind_Fluid};
  for (int32_t a = 0; a < step.actorCount; ++a) {
    vpActorStats s = vpDefaultActorStats();
    std::memset(&s, 0xFF, sizeof s);  // every field must be written
    s.structSize = sizeof s;
    ASSERT_VP_OK(vpWorldGetActorStats(w.id, a, &s));
    EXPECT_EQ(s.kind, expectedKind[a]);
    EXPECT_EQ(s.priority, expectedPriority[a]) << "actor " << a;
    EXPECT_EQ(s.failedPhases, 0u) << "actor " << a;
    EXPECT_EQ(s.interval, 1) << "actor " << a;
    EXPECT_TRUE(s.completedStep == 0 || s.completedStep == 1) << s.completedStep;
    EXPECT_TRUE(s.progress >= 0.0f && s.progress <= 1.0f) << s.progress;
    EXPECT_GE(s.slices, 0);
    EXPECT_TRUE(s.residual >= 0.0f) << s.residual;
    EXPECT_TRUE(s.floorMissed == 0 || s.floorMissed == 1) << s.floorMissed;
  }
  // The per-actor getters give the same record.
  vpActorStats byId = vpDefaultActorStats();
  ASSERT_VP_OK(vpDeformableGetStats(jellyId, &byId));
  EXPECT_EQ(byId.priority, 7);
  EXPECT_EQ(byId.interval, 1);
  ASSERT_VP_OK(vpFluidGetStats(smokeId, &byId));
  EXPECT_EQ(byId.priority, -3);
  EXPECT_EQ(byId.interval, 1);
}

TEST(CApiWorld, GravityAndBudgetSetters) {
  ScopedWorld w;
  vpVec3 g;
  ASSERT_VP_OK(vpWorldGetGravity(w.id, &g));
  EXPECT_FLOAT_EQ(g.y, -9.81f);
  ASSERT_VP_OK(vpWorldSetGravity(w.id, vpVec3{0, -1.62f, 0}));
  ASSERT_VP_OK(vpWorldGetGravity(w.id, &g));
  EXPECT_FLOAT_EQ(g.y, -1.62f);
  EXPECT_EQ(vpWorldSetGravity(w.id, vpVec3{0, NAN, 0}), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("gravity"));
  ASSERT_VP_OK(vpWorldGetGravity(w.id, &g));
  EXPECT_FLOAT_EQ(g.y, -1.62f);  // unchanged
  ASSERT_VP_OK(vpWorldSetFrameBudget(w.id, 8.0f));
  EXPECT_EQ(vpWorldSetFrameBudget(w.id, -1.0f), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("frameBudgetMs = -1"));
  ASSERT_VP_OK(vpWorldStep(w.id, 0.01f));
  vpStepStats stats = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &stats));
  EXPECT_FLOAT_EQ(stats.budgetMs, 8.0f);
}

TEST(CApiWorld, StepRejectsBadTimeSteps) {
  ScopedWorld w;
  for (float dt : {0.0f, -0.01f, NAN, INFINITY, 2.0f}) {
    EXPECT_EQ(vpWorldStep(w.id, dt), vpStatus_InvalidArgument) << dt;
    EXPECT_TRUE(lastErrorContains("dt = "));
  }
  vpStepStats stats = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &stats));
  EXPECT_EQ(stats.stepIndex, 0u);
}

TEST(CApiWorld, WorldDefRejectsBadValues) {
  struct Case {
    const char* field;
    void (*mutate)(vpWorldDef&);
    vpStatus status;
  } cases[] = {
      {"gravity", [](vpWorldDef& d) { d.gravity.x = NAN; }, vpStatus_InvalidArgument},
      {"workerCount = 0", [](vpWorldDef& d) { d.workerCount = 0; }, vpStatus_InvalidArgument},
      {"workerCount = 65", [](vpWorldDef& d) { d.workerCount = 65; }, vpStatus_InvalidArgument},
      {"frameBudgetMs = -2", [](vpWorldDef& d) { d.frameBudgetMs = -2; }, vpStatus_InvalidArgument},
      {"frameBudgetMs = nan", [](vpWorldDef& d) { d.frameBudgetMs = NAN; }, vpStatus_InvalidArgument},
      {"rigidMaxSubstep = 0", [](vpWorldDef& d) { d.rigidMaxSubstep = 0; }, vpStatus_InvalidArgument},
      {"vpWorldDef.structSize = 3", [](vpWorldDef& d) { d.structSize = 3; }, vpStatus_VersionMismatch},
      {"enqueueTask and finishTask", [](vpWorldDef& d) { d.finishTask = [](void*, void*) {}; }, vpStatus_InvalidArgument},
      {"device = 3", [](vpWorldDef& d) { d.device = 3; }, vpStatus_InvalidArgument},
      {"device = -1", [](vpWorldDef& d) { d.device = -1; }, vpStatus_InvalidArgument},
  };
  for (const Case& c : cases) {
    vpWorldDef def = vpDefaultWorldDef();
    c.mutate(def);
    vpWorldId id{77, 77};
    EXPECT_EQ(vpWorldCreate(&def, &id), c.status) << c.field;
    EXPECT_TRUE(lastErrorContains(c.field)) << vpGetLastError() << " / " << c.field;
    EXPECT_EQ(id.index1, 77);  // output untouched on failure
  }
  EXPECT_EQ(vpWorldCreate(nullptr, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("def is NULL"));
}

TEST(CApiWorld, LoadSceneAndFindColliders) {
  ScopedWorld w;
  ASSERT_VP_OK(vpWorldLoadScene(w.id, VP_TEST_DATA_DIR "/scenes/stack.json"));
  int32_t count = 0;
  ASSERT_VP_OK(vpWorldGetColliderCount(w.id, &count));
  EXPECT_EQ(count, 8);
  vpColliderId ids[16];
  int32_t written = 0;
  ASSERT_VP_OK(vpWorldGetColliders(w.id, ids, 3, &written));
  EXPECT_EQ(written, 3);
  vpColliderId spinner;
  ASSERT_VP_OK(vpWorldFindCollider(w.id, "spinner", &spinner));
  vpBodyType type;
  ASSERT_VP_OK(vpColliderGetBodyType(spinner, &type));
  EXPECT_EQ(type, vpBodyType_Kinematic);
  EXPECT_EQ(vpWorldFindCollider(w.id, "nobody", &spinner), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("\"nobody\""));
}

TEST(CApiWorld, BrokenSceneChangesNothing) {
  ScopedWorld w;
  const std::string path = ::testing::TempDir() + "/broken_scene.json";
  FILE* f = fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  fputs(R"({"world": {"frameBudgetMs": 1}, "colliders": [{"shape": {"type": "plane"}}, {"shape": {"type": "box", "halfExtents": [1, -1, 1]}}]})", f);
  fclose(f);
  EXPECT_EQ(vpWorldLoadScene(w.id, path.c_str()), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("$.colliders[1]: shape.halfExtents.y = -1"));
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetColliderCount(w.id, &count));
  EXPECT_EQ(count, 0);
  EXPECT_EQ(vpWorldLoadScene(w.id, nullptr), vpStatus_InvalidArgument);
}

// The CPU by default; Auto takes the CPU where no device is usable; Cuda there is refused,
// naming the field. Each world says where its deformable's solve ran.
TEST(CApiWorld, TheDeviceChoiceFallsToTheCpuOnlyWhenAskedToChoose) {
  EXPECT_EQ(vpDefaultWorldDef().device, vpDevice_Cpu);
  vpBuildInfo info;
  ASSERT_VP_OK(vpGetBuildInfo(&info));
  for (vpDevice device : {vpDevice_Cpu, vpDevice_Auto, vpDevice_Cuda}) {
    vpWorldDef def = vpDefaultWorldDef();
    def.device = device;
    vpWorldId id{};
    if (device == vpDevice_Cuda && info.cudaDeviceCount == 0) {
      EXPECT_EQ(vpWorldCreate(&def, &id), vpStatus_Unsupported);
      EXPECT_TRUE(lastErrorContains("device = 2 (Cuda): no usable CUDA device")) << vpGetLastError();
      continue;
    }
    ASSERT_VP_OK(vpWorldCreate(&def, &id));
    vpDeformableDef d = vpDefaultDeformableDef();
    const float vertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int32_t tets[4] = {0, 1, 2, 3};
    d.vertices = vertices;
    d.vertexCount = 4;
    d.tets = tets;
    d.tetCount = 1;
    vpDeformableId body;
    ASSERT_VP_OK(vpDeformableCreate(id, &d, &body));
    ASSERT_VP_OK(vpWorldStep(id, 1.0f / 60.0f));
    vpActorStats s;
    s.structSize = sizeof s;
    ASSERT_VP_OK(vpWorldGetActorStats(id, 1, &s));
    EXPECT_EQ(s.kind, vpActorKind_Deformable);
    const bool onDevice = device == vpDevice_Cuda || (device == vpDevice_Auto && info.cudaDeviceCount > 0);
    EXPECT_EQ(s.device, onDevice ? vpDevice_Cuda : vpDevice_Cpu) << device;
    ASSERT_VP_OK(vpWorldDestroy(id));
  }
}

// Each device the build info counts has a name and memory; any other index is refused naming
// the range.
TEST(CApiWorld, DeviceInfoForEachCountedDeviceAndNoOther) {
  vpBuildInfo build;
  ASSERT_VP_OK(vpGetBuildInfo(&build));
  for (int32_t d = 0; d < build.cudaDeviceCount; ++d) {
    vpDeviceInfo info = vpDefaultDeviceInfo();
    ASSERT_VP_OK(vpGetDeviceInfo(d, &info));
    EXPECT_GT(std::strlen(info.name), 0u);
    EXPECT_GT(info.totalMemoryBytes, 0u);
    EXPECT_GE(info.computeCapabilityMajor, 5);
    EXPECT_GT(info.multiprocessorCount, 0);
  }
  vpDeviceInfo info = vpDefaultDeviceInfo();
  EXPECT_EQ(vpGetDeviceInfo(build.cudaDeviceCount, &info), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("device = " + std::to_string(build.cudaDeviceCount) + ": must be in [0, " +
                                std::to_string(build.cudaDeviceCount) + ")"))
      << vpGetLastError();
  EXPECT_EQ(vpGetDeviceInfo(-1, &info), vpStatus_InvalidArgument);
  EXPECT_EQ(vpGetDeviceInfo(0, nullptr), vpStatus_InvalidArgument);
}

TEST(CApiWorld, BuildInfoAnswersWithoutAGpu) {
  vpBuildInfo info;
  ASSERT_VP_OK(vpGetBuildInfo(&info));
  EXPECT_GE(info.cudaDeviceCount, 0);
  EXPECT_GE(info.hardwareThreads, 1);
  if (!info.cudaCompiled) {
    EXPECT_EQ(info.cudaDeviceCount, 0);
  }
}

}  // namespace

namespace {

TEST(CApiWorld, EveryStatusHasItsName) {
  const char* names[] = {"Ok", "InvalidArgument", "InvalidId", "OutOfMemory", "Unsupported", "IoError",
                         "ParseError", "Busy", "Diverged", "VersionMismatch", "Internal", "PhaseFailed", "NotConverged"};
  for (int s = vpStatus_Ok; s <= vpStatus_NotConverged; ++s) EXPECT_STREQ(vpStatusName(static_cast<vpStatus>(s)), names[s]);
}

}  // namespace
