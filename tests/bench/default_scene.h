// What the benchmarks of the default scene (sample_host/scenes/default.json) share: the world
// the sample host runs it in, and percentiles of per-frame figures.
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include "scene/scene_loader.h"
#include "world.h"

namespace vp::bench {

// Two workers, as the sample host; null after a failed load (lastError() says why).
inline std::unique_ptr<World> defaultSceneWorld() {
  WorldConfig config;
  config.workerCount = 2;
  std::unique_ptr<World> world;
  if (!ok(World::create(config, &world)) || !ok(loadScene(*world, VP_SAMPLE_SCENE))) return nullptr;
  return world;
}

inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

}  // namespace vp::bench
