// The viscous traction of a fluid on a deforming closed surface (a deformable's boundary), as
// forces on its vertices, added to its pressure load (surface_pressure_load.h).
//
// It is what the fluid's last viscous step (viscosity.h) gave the fluid faces next to the
// surface through their solid terms, taken back from the surface: a face f whose velocity
// those terms changed by du took momentum rho h^3 du from the solids over the step's dt, so
// the surface takes -rho h^3 du / dt along f's axis. The exchange is then equal and opposite
// by construction; an estimate of the wall shear from the velocity field would not match what
// the fluid's step took (a staircase boundary couples over more links than the surface's
// area). Each face's share goes to the surface point nearest its centre, within kReachCells
// cells (the solid terms couple across one cell), split among that triangle's vertices by
// their barycentric weights; a face farther away exchanged with another solid.
// Limit: a face within reach of the surface and of another solid gives the surface both.
#pragma once

#include "collide/face_coverage.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/surface_pressure_load.h"
#include "fluid/viscosity.h"

namespace vp {

constexpr double kReachCells = 1.5;

// `surface` a deforming surface; `work` the viscous step's workspace after it solved (nothing
// is added otherwise); dt the time step it took. Adds to load->vertexForces (sized to the
// surface's vertices) and to load->total's force and torque (about the origin).
void addViscousTraction(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                        const PreparedCollider& surface, SurfacePressureLoad* load);

}  // namespace vp
