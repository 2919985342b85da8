// The same scene stepped with different worker counts must give bitwise-equal results.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "scene/scene_loader.h"
#include "world.h"

namespace vp {
namespace {

std::vector<double> runScene(int workers, int steps, const char* scene = VP_TEST_DATA_DIR "/scenes/stack.json") {
  WorldConfig config;
  config.workerCount = workers;
  std::unique_ptr<World> world;
  EXPECT_EQ(World::create(config, &world), Status::Ok);
  EXPECT_EQ(loadScene(*world, scene), Status::Ok) << lastError();
  // A budget cut depends on wall-clock time, so determinism is promised for steps the budget
  // does not cut (or for a host-injected clock); the comparison runs unbudgeted.
  EXPECT_EQ(world->setFrameBudget(0.0), Status::Ok);
  for (int i = 0; i < steps; ++i) EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok);
  std::vector<double> state;
  for (ColliderHandle h : world->colliderHandles()) {
    const Pose p = world->collider(h)->pose();
    state.insert(state.end(), {p.position.x(), p.position.y(), p.position.z(), p.rotation.x(), p.rotation.y(),
                               p.rotation.z(), p.rotation.w()});
  }
  for (DeformableHandle h : world->deformableHandles()) {
    const DeformableBody& d = *world->deformable(h);
    state.insert(state.end(), d.positions().begin(), d.positions().end());
    state.insert(state.end(), d.velocities().begin(), d.velocities().end());
  }
  for (FluidHandle h : world->fluidHandles()) {
    const FluidActor& f = *world->fluid(h);
    for (int a = 0; a < 3; ++a) state.insert(state.end(), f.grid().velocity[a].begin(), f.grid().velocity[a].end());
    for (const std::vector<double>* field : {&f.smokeDensity(), &f.levelSet(), &f.pressure()})
      state.insert(state.end(), field->begin(), field->end());
  }
  return state;
}

TEST(Determinism, SameSceneWithOneAndTwoWorkersIsBitwiseEqual) {
  const std::vector<double> one = runScene(1, 180);
  const std::vector<double> two = runScene(2, 180);
  const std::vector<double> again = runScene(2, 180);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(two.data(), again.data(), two.size() * sizeof(double)), 0);
  // Something actually moved (a test of a frozen scene would prove nothing).
  const std::vector<double> start = runScene(1, 0);
  EXPECT_NE(std::memcmp(start.data(), one.data(), one.size() * sizeof(double)), 0);
}

// Deformables assemble through parallel element colours and reduce CG dot products over
// fixed chunks: 1, 2 and 3 workers must agree to the last bit.
TEST(Determinism, DeformableSceneIsBitwiseEqualForAnyWorkerCount) {
  const char* scene = VP_TEST_DATA_DIR "/scenes/jelly_bridge.json";
  const std::vector<double> one = runScene(1, 60, scene);
  for (int workers : {2, 3}) {
    const std::vector<double> other = runScene(workers, 60, scene);
    ASSERT_EQ(one.size(), other.size());
    EXPECT_EQ(std::memcmp(one.data(), other.data(), one.size() * sizeof(double)), 0) << workers << " workers";
  }
}

// Fluids: advection, level set upkeep, the pressure solve and the loads on a floating body
// all run in fixed chunks too.
TEST(Determinism, FluidSceneIsBitwiseEqualForAnyWorkerCount) {
  const char* scene = VP_TEST_DATA_DIR "/scenes/fluid_pair.json";
  const std::vector<double> one = runScene(1, 30, scene);
  for (int workers : {2, 3}) {
    const std::vector<double> other = runScene(workers, 30, scene);
    ASSERT_EQ(one.size(), other.size());
    EXPECT_EQ(std::memcmp(one.data(), other.data(), one.size() * sizeof(double)), 0) << workers << " workers";
  }
  // Before any step the pressure has no values yet, so the sizes differ too.
  EXPECT_NE(runScene(1, 0, scene), one);
}

}  // namespace
}  // namespace vp
