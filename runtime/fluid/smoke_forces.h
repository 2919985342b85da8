// Body forces of smoke, applied to the MAC face velocities before the pressure projection.
//
// Buoyancy (Boussinesq, Fedkiw, Stam, Jensen 2001): f = (-alpha d + beta (T - T_ambient)) up,
// with up = -gravity / |gravity| (no buoyancy without gravity). Evaluated at each face from
// the mean of its two cells.
//
// Vorticity confinement (Fedkiw et al. 2001): f = epsilon h (N x omega), N = grad|omega| /
// |grad|omega||, which puts back the small swirls that numerical dissipation removes;
// h makes the force vanish under refinement (the scheme stays consistent).
#pragma once

#include <vector>

#include "core/allocator.h"
#include "core/task_system.h"
#include "fluid/fluid_desc.h"
#include "fluid/mac_grid.h"

namespace vp {

void applyBuoyancy(TaskSystem& tasks, MacGrid& grid, const Array<double>& smokeDensity,
                   const Array<double>& temperature, const SmokeParameters& params, const Vec3& gravity,
                   double dt);

// Per cell, vectors as 3 doubles (gpu_kernels/smoke_force_kernels.h).
struct VorticityWorkspace {
  Array<double> omega;
  Array<double> omegaNorm;
  Array<double> force;  // the cell-centred velocity until omega is done
};

void applyVorticityConfinement(TaskSystem& tasks, MacGrid& grid, double epsilon, double dt,
                               VorticityWorkspace& work);

// values *= exp(-rate dt): exact decay for any dt.
void dissipate(Array<double>& values, double rate, double dt);

}  // namespace vp
