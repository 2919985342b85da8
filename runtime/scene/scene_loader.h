// JSON scene files -> world. The format is documented in docs/scene_format.md.
#pragma once

#include <string>

#include "core/status.h"

namespace vp {

class World;

// Parses and validates the whole file first, then applies it: on any error the world is
// unchanged and the message starts with the JSON path of the problem.
Status loadScene(World& world, const std::string& path);
Status loadSceneFromString(World& world, const std::string& text, const std::string& baseDirectory);

}  // namespace vp
