// The viscous traction of a fluid on a body, as a drag: on a deforming closed surface (a
// deformable's boundary) on its vertices (surface_pressure_load.h, VertexDrag); on a rigid
// collider as a force and a torque (collide/solid_motion.h, RigidDrag).
//
// It is what the fluid's last viscous step (viscosity.h) gave the fluid faces next to the
// body through their solid terms, taken back from the body: a face f whose velocity those
// terms changed by du took momentum rho h^3 du from the solids over the step's dt, so the body
// takes -rho h^3 du / dt along f's axis. The exchange is then equal and opposite by
// construction; an estimate of the wall shear from the velocity field would not match what the
// fluid's step took (a staircase boundary couples over more links than the surface's area).
// A face within kReachCells cells of the body gives it its share; a face farther away exchanged
// with another solid.
//   Deforming surface: the share goes to the surface point nearest the face's centre, split
//   among that triangle's vertices by their barycentric weights (the nodes carry it).
//   Rigid collider: the share acts at the face's centre, where the fluid's momentum changed, so
//   the body takes the fluid's change of angular momentum exactly too. Which faces are within
//   reach is read from signedDistanceBound, a lower bound outside a convex hull: near a hull's
//   corners a face a little farther than the reach counts too.
// Held explicitly over the fluid's step, the traction would make a body light against the
// drag of the faces it couples to (D T > m, D the drag a unit of its velocity meets, T its
// step) overshoot the liquid's velocity each step, and further each time (docs/choices.md has
// the light balls that did). So a body takes it as a drag that its step solves with its new
// motion (backward Euler), each face's D_f being rho h^3 times its coupling to the solids over
// dt (ViscosityWorkspace::solidCoupling), a bound on the drag (the liquid's own response to the
// body lowers it), and the force at rest being what the step took plus the drag at the motion
// it saw. Apart from the pressure's load, it takes no part in the added-mass stabilization,
// which would scale it down (it carries no added mass).
//   Deforming surface: per vertex and axis the drag C of its faces (SurfacePressureLoad::drag).
//   Rigid collider: per axis D, the sum of D_f over the faces along it, and for the spin
//   D_w = sum D_f (r x e_a)(r x e_a)^T with r each face's arm (RigidDrag); the couplings between
//   the velocity and the spin (zero for a body symmetric about its centre) are left out.
// Limit: a face within reach of the body and of another solid gives the body both.
#pragma once

#include "collide/face_coverage.h"
#include "collide/solid_motion.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/surface_pressure_load.h"
#include "fluid/viscosity.h"

namespace vp {

// The solid terms couple a face to its neighbours one cell away, and a neighbour takes the
// solid's velocity where the body touches its square, whose points are within half a diagonal
// of its centre.
constexpr double kReachCells = 1.0 + 0.70710678118654757;

// `surface` a deforming surface; `work` the viscous step's workspace after it solved (nothing
// is added otherwise); dt the time step it took. Adds to load->drag (sized to the surface's
// vertices when empty) and to load->total's force and torque (about the origin).
void addViscousTraction(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                        const PreparedCollider& surface, SurfacePressureLoad* load);

// The same for a rigid collider, as a drag about its centre of mass (the prepared shape's
// translation), added to `drag`.
void addViscousTractionOnCollider(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                                  const PreparedCollider& collider, RigidDrag* drag);

}  // namespace vp
