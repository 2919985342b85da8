// The viscous traction of a fluid on a body: on a deforming closed surface (a deformable's
// boundary) as forces on its vertices, added to its pressure load (surface_pressure_load.h);
// on a rigid collider as a force and a torque, added to its pressure load (pressure_forces.h).
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
//   among that triangle's vertices by their barycentric weights (the nodes carry it), as a
//   drag apart from the pressure's forces (SurfacePressureLoad::drag).
//   Rigid collider: the share acts at the face's centre, where the fluid's momentum changed, so
//   the body takes the fluid's change of angular momentum exactly too. Which faces are within
//   reach is read from signedDistanceBound, a lower bound outside a convex hull: near a hull's
//   corners a face a little farther than the reach counts too.
// Held explicitly over the fluid's step, the traction would make a body light against the
// drag of the faces it couples to (D T > m, D the drag a unit of its velocity meets, T the
// time the load acts) overshoot the liquid's velocity each step, and further each time
// (docs/choices.md has the light balls that did). So a body takes it as backward Euler takes a
// drag -D (v - v_liquid), each face's D_f being rho h^3 times its coupling to the solids over
// dt (ViscosityWorkspace::solidCoupling), a bound on the drag (the liquid's own response to the
// body lowers it):
//   Deforming surface: per vertex and axis the drag C of its faces, which the body's implicit
//   step solves with its new velocity v': f(v') = f + C (v_seen - v'), f the share at the
//   velocity v_seen the step saw. Apart from the pressure's forces, it takes no part in their
//   added-mass stabilization (deform/fluid_immersion.h), which would scale it down.
//   Rigid collider: m (m + D T)^-1 of the force per axis and I (I + D_w T)^-1 of the torque,
//   D summed over the faces each axis's force comes from, D_w the same with each face's arm,
//   sum D_f (r x e_a)(r x e_a)^T; T the fluid's step.
// Limit: a face within reach of the body and of another solid gives the body both.
#pragma once

#include "collide/face_coverage.h"
#include "collide/solid_motion.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/pressure_forces.h"
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

// The same for a rigid collider: adds the force and the torque about `centre` (its centre of
// mass) to load, as the body of `inertia` takes them over `heldFor` seconds (unscaled where
// inertia.mass is 0).
void addViscousTractionOnCollider(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                                  const PreparedCollider& collider, const Vec3& centre, const RigidInertia& inertia,
                                  double heldFor, PressureLoad* load);

}  // namespace vp
