// What the deformable contact benchmarks share: an unbudgeted world on two workers with a
// ground plane (y = 0).
#pragma once

#include <memory>

#include "world.h"

namespace vp::bench {

// Null when the world or the plane could not be made (lastError() says why).
inline std::unique_ptr<World> worldOnGround() {
  WorldConfig config;
  config.workerCount = 2;
  config.frameBudgetMs = 0.0;
  std::unique_ptr<World> world;
  if (!ok(World::create(config, &world))) return nullptr;
  ColliderDesc ground;
  ground.shape.type = ShapeType::Plane;
  ColliderHandle groundHandle;
  if (!ok(world->createCollider(ground, &groundHandle))) return nullptr;
  return world;
}

}  // namespace vp::bench
