// Body forces of smoke (and a liquid's gravity), applied to the MAC face velocities before the
// pressure projection, as passes over grid rows that a fluid step may run in slices.
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
#include "core/slab_passes.h"
#include "fluid/fluid_desc.h"
#include "fluid/mac_grid.h"

namespace vp {

// Per cell, vectors as 3 doubles (gpu_kernels/smoke_force_kernels.h).
struct VorticityWorkspace {
  Array<double> omega;
  Array<double> omegaNorm;
  Array<double> force;  // the cell-centred velocity until omega is done
};

// The smoke's body forces over dt as passes (core/slab_passes.h) added to `passes`, in order:
// buoyancy, vorticity confinement, then the dissipation of density and temperature (values *=
// exp(-rate dt), exact decay for any dt). The arrays must outlive the passes. However the
// passes are sliced, the results are bitwise those of one whole run.
void addSmokeForcePasses(SlabPasses& passes, MacGrid& grid, Array<double>& smokeDensity, Array<double>& temperature,
                         const SmokeParameters& params, const Vec3& gravity, double dt, VorticityWorkspace& work);

// A liquid's gravity over dt (u += dt g on every face) as passes added to `passes`.
void addGravityPasses(SlabPasses& passes, MacGrid& grid, const Vec3& gravity, double dt);

}  // namespace vp
