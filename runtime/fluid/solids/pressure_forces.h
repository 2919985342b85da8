// Pressure force and torque of a fluid on one collider.
//
// F = -integral over the body of grad p (the pressure extended smoothly into the solid), which
// equals the surface integral of -p n over its wetted part. Discretely, over the MAC faces
// that the collider covers (c_f of face f):
//     F   = -sum_f c_f h^2 (p_high - p_low) e_a,
//     tau = -sum_f c_f h^2 (x_f - centre) x (p_high - p_low) e_a,
// i.e. the pressure gradient at each face times the solid volume the face stands for: c_f is
// the solid fraction of the face's dual cell (the h^3 box centred on it).
// Inside the solid the pressure is extended layer by layer from the known cells (fluid cells,
// and air cells of a liquid at p = 0) by linear extrapolation along each axis, averaged over
// the axes that have a known neighbour. A hydrostatic pressure is linear, so it is extended
// exactly and the buoyancy is rho g times sum_f c_f h^3, the submerged volume up to the
// slicing of c_f (pressure_forces.cpp), for any placement of the body on the grid.
//
// Why not the surface form with each cut cell's centre pressure: a cut cell's centre can lie
// up to h/2 (inside the solid or outside) from the interface it stands for, so the force on
// a body that sits between grid lines is biased by up to rho g h per unit area; a floating box
// then settles visibly too deep or too high and bobs as it crosses grid lines.
#pragma once

#include "collide/face_coverage.h"
#include "core/math_types.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

struct PressureLoad {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();  // about `centre`
  // Fluid density times the body's volume in the fluid (not in air): the added mass of a
  // body in potential flow is of this order (half of it for a sphere, about all of it for a
  // box moving across a face), which is what the coupling's stabilization needs.
  double addedMass = 0.0;
};

// A liquid whose weight a load can leave out: its level set (null: none, smoke) and gravity.
struct LiquidWeight {
  const double* liquidPhi = nullptr;
  Vec3 gravity = Vec3::Zero();
};

// `less`: the hydrostatic pressure under its free surface (hydrostaticLoadOnCollider) is taken
// off the solve's in the same sums, which gives the dynamic part that a fluid step hands on.
PressureLoad pressureLoadOnCollider(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                                    const double* pressure, double density, const PreparedCollider& collider,
                                    const Vec3& centre, const LiquidWeight* less = nullptr);

// The part of that load that is the liquid's weight, by the same sums over the same faces with
// the hydrostatic pressure under the free surface of liquidPhi
// (fluid/surface/hydrostatic_pressure.h) in place of the solve's: a body takes it anew at its
// own steps from the liquid's last level set. Zero for smoke (liquidPhi null).
PressureLoad hydrostaticLoadOnCollider(const MacGrid& grid, const double* liquidPhi, double density,
                                       const Vec3& gravity, const PreparedCollider& collider, const Vec3& centre);

}  // namespace vp
