// A fluid step's energy for the divergence guard (core/step_energy.h). The kinetic energy is
// ½ ρ h³ Σ open(f) u(f)² over the faces of the fluid (a liquid's: faces beside a liquid cell).
// What may put energy in (the forces, the emitters, the moving solids, through the advection
// and the projection) is known only by a bound, from the triangle inequality in the norm
// √(2 E) over the fluid's mass M:
//   ‖u'‖ ≤ ‖u‖ + ‖a‖ dt + ‖u_boundary‖,  each ‖·‖ ≤ √M times its largest speed,
// so the step's energy may reach (√E + √(M / 2) v)² with v = a dt + the fastest solid or
// emitter, a the largest body-force acceleration: gravity for a liquid; for smoke buoyancy
// α d_max + β |T − T_ambient|_max and vorticity confinement ε h |ω| ≤ 4 √3 ε u_max (|ω| from
// differences of cell-centred speeds over at least h). The projection's share of the moving
// solids (in a narrow gap the flow outruns the solid) and the advection's (interpolation may
// gather energy where it compresses) are not bounded: kGrowthFactor covers them.
#pragma once

#include "core/step_energy.h"
#include "core/task_system.h"
#include "fluid/fluid_desc.h"
#include "fluid/mac_grid.h"

namespace vp {

// ½ ρ h³ Σ open u² over the fluid's faces; liquidPhi: the level set (null: smoke, every face).
double fluidKineticEnergy(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                          const double* liquidPhi, double density);

// What a step of dt may put into a fluid of kineticStart and mass M, whose body forces
// accelerate by at most `acceleration` and whose solids and emitters move at most at
// `boundarySpeed`: (√E + √(M / 2) v)² − E, v = acceleration dt + boundarySpeed.
double fluidSourceWorkBound(double kineticStart, double mass, double acceleration, double boundarySpeed, double dt);

// max |values − from| (0 for none; NaN counts as infinitely far).
double largestDeviation(TaskSystem& tasks, const Array<double>& values, double from);

// The largest acceleration of the smoke's body forces within a step whose speeds stay below
// `speed`, whose density stays below `densityMax` and whose temperature within
// `heatMax` of ambient.
double smokeAccelerationBound(const SmokeParameters& smoke, double gravity, double densityMax, double heatMax,
                              double speed);

}  // namespace vp
