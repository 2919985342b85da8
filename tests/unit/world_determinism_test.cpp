// The same scene stepped with different worker counts must give bitwise-equal results.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "../budget/tick_clock.h"
#include "scene/scene_loader.h"
#include "world.h"

namespace vp {
namespace {

// budgetMs > 0 needs a clock: a budget cut depends on wall-clock time, so determinism is
// promised for steps the budget does not cut or for a host-injected clock.
std::vector<double> runScene(int workers, int steps, const char* scene = VP_TEST_DATA_DIR "/scenes/stack.json",
                             double budgetMs = 0.0, Clock clock = Clock{}) {
  WorldConfig config;
  config.workerCount = workers;
  config.clock = clock;
  std::unique_ptr<World> world;
  EXPECT_EQ(World::create(config, &world), Status::Ok);
  EXPECT_EQ(loadScene(*world, scene), Status::Ok) << lastError();
  EXPECT_EQ(world->setFrameBudget(budgetMs), Status::Ok);  // after the scene's own budget
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
    for (const Array<double>* field : {&f.smokeDensity(), &f.levelSet(), &f.pressure()})
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

// FNV-1a over the state's bytes: one number to pin.
uint64_t stateHash(const std::vector<double>& state) {
  uint64_t h = 1469598103934665603ull;
  const auto* bytes = reinterpret_cast<const unsigned char*>(state.data());
  for (size_t i = 0; i < state.size() * sizeof(double); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  return h;
}

// The default scene (sample_host/scenes/default.json: rigid stack, three deformables, a
// liquid tank with a paddle and a buoy, a smoke plume with a turning blade) after 120 frames, as one pinned hash (as Box2D
// pins its). Any change to the results of any stage changes it: such a commit re-pins it and
// says why. The pinned values hold for this toolchain (Debian 12's GCC, Bullet, Eigen, libm).
constexpr const char* kDefaultScene = VP_TEST_DATA_DIR "/../../sample_host/scenes/default.json";
constexpr uint64_t kDefaultSceneHash = 0x5bd0a1d1db54b358ull;
constexpr uint64_t kDefaultSceneTickBudgetHash = 0x1f3531db3fa07a13ull;

TEST(Determinism, DefaultSceneHashIsPinnedForAnyWorkerCount) {
  for (int workers : {1, 2, 3, 8}) {
    const uint64_t h = stateHash(runScene(workers, 120, kDefaultScene));
    EXPECT_EQ(h, kDefaultSceneHash) << workers << " workers: " << std::hex << h;
  }
}

// Under a frame budget counted by the tick clock: what the budget cuts and paces depends only
// on clock readings, and an injected clock is read in plan order on the stepping thread, so
// the run repeats to the bit for any worker count.
TEST(Determinism, DefaultSceneHashUnderATickClockBudgetIsPinnedForAnyWorkerCount) {
  for (int workers : {1, 2, 3, 8}) {
    testutil::TickClock clock;
    const uint64_t h = stateHash(runScene(workers, 120, kDefaultScene, 16.0, clock.clock()));
    EXPECT_EQ(h, kDefaultSceneTickBudgetHash) << workers << " workers: " << std::hex << h;
  }
}

}  // namespace
}  // namespace vp
