// Many worlds on many threads at once: each thread's world gives the same results as a serial
// run, and errors stay with the thread that caused them.
#include <atomic>
#include <cstring>
#include <thread>
#include <vector>

#include "capi_test_support.h"

namespace {

// Every thread builds and steps its own world; results must match a serial run exactly.
TEST(CApiThreads, ManyWorldsFromDifferentThreads) {
  auto simulate = [](float x, vpTransform* out) {
    vpWorldDef def = vpDefaultWorldDef();
    def.workerCount = 2;
    vpWorldId w;
    if (vpWorldCreate(&def, &w) != vpStatus_Ok) return false;
    vpColliderDef ground = vpDefaultColliderDef();
    ground.shape.type = vpShapeType_Plane;
    vpColliderId g, b;
    vpColliderDef ball = dynamicBall(2.0f);
    ball.pose.position.x = x;
    ball.linearVelocity = vpVec3{1, 0, 0};
    bool ok = vpColliderCreate(w, &ground, &g) == vpStatus_Ok && vpColliderCreate(w, &ball, &b) == vpStatus_Ok;
    for (int i = 0; ok && i < 90; ++i) ok = vpWorldStep(w, 1.0f / 60.0f) == vpStatus_Ok;
    ok = ok && vpColliderGetPose(b, out) == vpStatus_Ok;
    return vpWorldDestroy(w) == vpStatus_Ok && ok;
  };
  const int kThreads = 8;
  std::vector<vpTransform> parallel(kThreads), serial(kThreads);
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      for (int round = 0; round < 3; ++round)
        if (!simulate(float(t), &parallel[t])) failures++;
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(failures.load(), 0);
  for (int t = 0; t < kThreads; ++t) {
    ASSERT_TRUE(simulate(float(t), &serial[t]));
    EXPECT_EQ(std::memcmp(&serial[t], &parallel[t], sizeof(vpTransform)), 0) << "thread " << t;
  }
}

// The thread-local last error of one thread is not overwritten by another thread's failure.
TEST(CApiThreads, LastErrorIsPerThread) {
  vpWorldId bogus{500, 1};
  ASSERT_EQ(vpWorldStep(bogus, 0.01f), vpStatus_InvalidId);
  std::thread other([] {
    vpWorldDef def = vpDefaultWorldDef();
    def.workerCount = -3;
    vpWorldId w;
    vpWorldCreate(&def, &w);
  });
  other.join();
  EXPECT_TRUE(lastErrorContains("world id (500, 1)"));
}

// What a world's actors hold after some frames, as bytes: the dynamic body's pose, each fluid's
// velocity grid, and each deformable's node positions.
std::vector<float> stateAfterFrames(const char* scene, int workerCount, int frames) {
  vpWorldDef def = unbudgetedWorldDef();
  def.workerCount = workerCount;
  ScopedWorld w(def);
  std::vector<float> state;
  if (vpWorldLoadScene(w.id, scene) != vpStatus_Ok) return state;
  for (int i = 0; i < frames; ++i)
    if (vpWorldStep(w.id, 1.0f / 60.0f) != vpStatus_Ok) return {};
  vpColliderId body;
  if (vpWorldFindCollider(w.id, "float", &body) == vpStatus_Ok) {
    vpTransform pose;
    vpColliderGetPose(body, &pose);
    state.insert(state.end(), {pose.position.x, pose.position.y, pose.position.z, pose.rotation.w});
  }
  vpFluidId fluids[4];
  int32_t fluidCount = 0;
  vpWorldGetFluids(w.id, fluids, 4, &fluidCount);
  for (int32_t f = 0; f < fluidCount; ++f) {
    int32_t nx, ny, nz;
    vpFluidGetResolution(fluids[f], &nx, &ny, &nz);
    std::vector<float> grid(3 * size_t(nx) * ny * nz);
    vpFluidGetVelocityGrid(fluids[f], grid.data(), int64_t(grid.size()));
    state.insert(state.end(), grid.begin(), grid.end());
  }
  vpDeformableId bodies[4];
  int32_t bodyCount = 0;
  vpWorldGetDeformables(w.id, bodies, 4, &bodyCount);
  for (int32_t d = 0; d < bodyCount; ++d) {
    int32_t nodes = 0;
    vpDeformableGetNodeCount(bodies[d], &nodes);
    std::vector<float> xyz(3 * size_t(nodes));
    vpDeformableGetPositions(bodies[d], xyz.data(), nodes);
    state.insert(state.end(), xyz.begin(), xyz.end());
  }
  return state;
}

// The built-in pool's threads share the fluids' and deformables' loops (and run the two fluids
// side by side); the results are bit for bit those of one thread.
TEST(CApiThreads, WorkerPoolGivesTheSerialResult) {
  for (const char* scene : {VP_TEST_DATA_DIR "/scenes/fluid_pair.json", VP_TEST_DATA_DIR "/scenes/jelly_bridge.json"}) {
    const std::vector<float> serial = stateAfterFrames(scene, 1, 4);
    ASSERT_FALSE(serial.empty()) << scene << ": " << vpGetLastError();
    for (int workers : {2, 3}) {
      const std::vector<float> pooled = stateAfterFrames(scene, workers, 4);
      ASSERT_EQ(pooled.size(), serial.size()) << scene;
      EXPECT_EQ(std::memcmp(pooled.data(), serial.data(), serial.size() * sizeof(float)), 0)
          << scene << " with " << workers << " workers";
    }
  }
}

}  // namespace
