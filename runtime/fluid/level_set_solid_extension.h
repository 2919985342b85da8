// The liquid level set inside solids: what a cell holds while a collider covers it is what it
// will hold when the collider moves on, so it must describe the liquid around the solid.
// Advection alone leaves whatever the solid's own motion dragged in (a floating body drags
// air under the surface, and the cells it uncovers then read as a bubble under it: the
// pressure there drops to zero and the body loses its buoyancy).
//
// Mostly-solid cells (open weight < 1/2, see cellOpenFractions) take, layer by layer from
// the fluid side, the mean phi of their already-known face neighbours: liquid below a
// floating body's waterline, air above it. Redistancing afterwards turns the values into
// distances again.
#pragma once

#include <cstdint>
#include <vector>

#include "fluid/face_fraction_field.h"

namespace vp {

void extendLevelSetIntoSolids(const MacGridSpec& grid, const std::vector<double>& cellWeights, std::vector<double>& phi,
                              std::vector<int64_t>& scratch);

}  // namespace vp
