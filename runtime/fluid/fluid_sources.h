// Where fluid comes from and goes: smoke emitters, liquid emitters, drains and the initial
// liquid, all given as FluidShape regions in world coordinates (fluid_desc.h).
//
// A cell is inside a shape when its centre is; a face when its centre is. Emitters act on
// whole cells rather than partial volumes: they are sources, not boundaries, and a smooth
// fraction would only soften their edge by half a cell.
#pragma once

#include <vector>

#include "core/allocator.h"
#include "fluid/fluid_desc.h"
#include "fluid/mac_grid.h"

namespace vp {

// Smoke: density += rate dt and temperature = emitter temperature inside; faces inside take
// the emitter's velocity.
void applySmokeEmitters(MacGrid& grid, const std::vector<FluidEmitter>& emitters, double dt,
                        Array<double>& smokeDensity, Array<double>& temperature);

// Liquid: phi = min(phi, shape distance) (the union with the shape); faces inside take the
// emitter's velocity.
void applyLiquidEmitters(MacGrid& grid, const std::vector<FluidEmitter>& emitters, Array<double>& phi);

// Liquid: phi = max(phi, -shape distance) (the shape is cut out of the liquid).
void applyDrains(const MacGrid& grid, const std::vector<FluidShape>& drains, Array<double>& phi);

// phi of the union of `regions` (+ a large positive value where there is none).
void initialLiquidLevelSet(const MacGrid& grid, const std::vector<FluidShape>& regions, Array<double>& phi);

}  // namespace vp
