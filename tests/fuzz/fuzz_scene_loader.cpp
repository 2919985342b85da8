// Fuzz target: the JSON scene loader (scene/scene_loader.h) on arbitrary text, into a fresh
// world; relative mesh paths resolve against tests/data/scenes. Any status is fine; a crash,
// a sanitizer report or a hang is not.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "scene/scene_loader.h"
#include "world.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vp::WorldConfig config;
  config.frameBudgetMs = 0.0;
  std::unique_ptr<vp::World> world;
  if (!vp::ok(vp::World::create(config, &world))) return 0;
  vp::loadSceneFromString(*world, std::string(reinterpret_cast<const char*>(data), size), VP_FUZZ_SCENE_DIR);
  return 0;
}
