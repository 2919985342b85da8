// The liquid's volume holds under any frame budget: a budget changes how many frames a fluid
// step spans (pacing) and where it is cut into slices, never how much liquid there is. On the
// default scene's tank (a paddle and a buoy standing in the water), with the tick clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene/scene_loader.h"
#include "tick_clock.h"
#include "world.h"

namespace vp {
namespace {

// The volume correction's own tolerance (VolumeCorrectionSettings::relativeTolerance) with
// room for the round-off of summing the level set over the grid.
constexpr double kVolumeTolerance = 1e-8;

TEST(LiquidVolumeUnderBudget, TheDefaultTankKeepsItsVolumeAt4And8And16Ms) {
  for (double budgetMs : {0.0, 4.0, 8.0, 16.0}) {
    testutil::TickClock clock;
    WorldConfig config;
    config.clock = clock.clock();
    std::unique_ptr<World> world;
    ASSERT_EQ(World::create(config, &world), Status::Ok) << lastError();
    ASSERT_EQ(loadScene(*world, VP_SCENE_DIR "/default.json"), Status::Ok) << lastError();
    ASSERT_EQ(world->setFrameBudget(budgetMs), Status::Ok);
    FluidHandle tank;
    ASSERT_TRUE(world->findFluid("tank", &tank));
    // What the scene defined, before any step: the solids in it displace it, not delete it.
    const double defined = world->fluid(tank)->liquidVolume();
    double worst = 0.0;
    for (int frame = 0; frame < 120; ++frame) {
      ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok) << lastError();
      worst = std::max(worst, std::abs(world->fluid(tank)->liquidVolume() / defined - 1.0));
    }
    EXPECT_GT(world->fluid(tank)->stepCount(), 10u) << "budget " << budgetMs << " ms";
    EXPECT_LT(worst, kVolumeTolerance) << "budget " << budgetMs << " ms";
  }
}

}  // namespace
}  // namespace vp
