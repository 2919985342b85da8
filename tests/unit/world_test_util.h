// A World for tests that must not depend on the machine's speed.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "world.h"

namespace vp {
namespace testutil {

// No frame budget (nothing is cut or paced by the clock) and two workers; null (and a test
// failure) if the world cannot be made.
inline std::unique_ptr<World> unbudgetedWorld(int workers = 2) {
  WorldConfig config;
  config.workerCount = workers;
  config.frameBudgetMs = 0.0;
  std::unique_ptr<World> world;
  EXPECT_EQ(World::create(config, &world), Status::Ok) << lastError();
  return world;
}

}  // namespace testutil
}  // namespace vp
