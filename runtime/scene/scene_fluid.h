// The "fluids" entries of JSON scene files (docs/scene_format.md) -> FluidDesc.
#pragma once

#include "fluid/fluid_desc.h"
#include "scene/json_fields.h"

namespace vp {

// Parses and validates one fluid; errors carry the JSON path.
Status parseFluid(const JsonObject& obj, FluidDesc* out);

}  // namespace vp
