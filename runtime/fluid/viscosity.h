// Implicit viscosity of a MAC velocity field on a cut-cell grid: one backward-Euler step of
//     du/dt = nu L u,   i.e.   (I - dt nu L) u_new = u_old   for each velocity component,
// so any nu dt / h^2 is stable (an explicit step needs nu dt / h^2 <= 1/6 in 3D, which a
// game liquid at 60 Hz breaks from nu ~ 1e-4 m^2/s at 1 cm cells).
//
// Unknowns: the faces the pressure projection updates, i.e. not on a Wall side, open
// (effectiveOpenFraction > 0) and, for a liquid, next to at least one liquid cell. The other
// faces keep their velocity. Each component lives on its own faces and is decoupled from
// the others, so the three systems are solved together as one block-diagonal one.
//
// L on face f, from its six same-axis neighbours n at distance h (h^2 L u_f = sum over n):
//   n an unknown      w (u_n - u_f) + (1 - w)(g - u_f),  w = min(A_f, A_n)
//   n closed by a     (g - u_f)          no-slip at the neighbour's centre,
//     solid                              g = the solid's velocity there (solidVelocity)
//   n on a Wall side  (0 - u_f)          no-slip, the wall is at distance h
//   n past a Wall     (-u_f - u_f)       no-slip, reflected ghost: the wall lies midway, h/2
//     (tangential)
//   n past an Open    nothing            zero normal gradient (the flow continues outside)
//     side
//   n in air          nothing            free surface, see below
// where A are the effective open fractions and g, for a pair of unknowns, is the solid
// velocity of the less open of the two: the covered share of the pair's coupling sees the
// solid. That keeps the operator symmetric (w is the same seen from either face) and makes
// the no-slip condition first-order accurate in the wall position, like the voxelized
// boundary of a solid that covers whole faces; a cut-cell distance to the wall would be
// second order but breaks the symmetry CG needs.
//
// Free surface: faces with air on both sides are not unknowns and add no term (zero normal
// gradient of each component). The exact condition, zero tangential traction, couples the
// components (du_t/dn = -du_n/dt); dropping the cross term is the usual approximation for
// visual liquids and keeps the components independent; it errs only where the surface
// is steep and sheared.
//
// Solve: CG (linalg/conjugate_gradient.h) with a Jacobi preconditioner (the diagonal is
// 1 + k nu dt / h^2 with k from 0 to 12 around solids and walls), warm-started from u_old,
// within the deadline; the operator is applied matrix-free from the fractions, with only
// the diagonal kept. Nothing is done when nu = 0.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/allocator.h"
#include "core/budget_clock.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/face_fraction_field.h"
#include "linalg/conjugate_gradient.h"

namespace vp {

struct ViscositySettings {
  // Relative residual |b - A u| / |b|, with b ~ u_old: the velocity error it leaves is that
  // fraction of the flow's speed, far below what advection loses per step.
  double tolerance = 1e-5;
  int maxIterations = 200;
  int minIterations = 2;  // run even past the deadline, like the pressure's
  // Keep what the solids gave each face (ViscosityWorkspace::solidChange) for a dynamic
  // body's traction; a stencil pass more after the solve, so only when one takes it.
  bool recordSolidExchange = false;
};

struct ViscosityStats {
  CgResult solve;        // iterations, residual, converged, cut by the budget
  int64_t unknowns = 0;  // faces solved for (0 when nu = 0: nothing was done)
};

// Per-step buffers kept between steps so a viscous fluid does not reallocate every frame.
struct ViscosityWorkspace {
  std::array<Array<int32_t>, 3> unknownOfFace;  // per face of each axis; -1: keeps its velocity
  std::array<int64_t, 4> axisBegin{};                  // unknowns of axis a: [axisBegin[a], axisBegin[a+1])
  Array<int64_t> face;                           // per unknown: its face index on its axis
  Array<double> open, diagonal, rhs, velocity;   // per unknown
  Array<int64_t> rowStart;                       // per face row (j, k) of an axis: first unknown
  CgWorkspace cg;
  // Per unknown, after a solve that recorded it (ViscositySettings::recordSolidExchange): the
  // change of its velocity that its solid terms made, nu dt / h^2 times the sum over its solid
  // neighbours of weight * (g - u_new), and that change per unit of the solids' velocity g,
  // nu dt / h^2 times the sum of those weights.
  Array<double> solidChange, solidCoupling;
  // The unknowns whose solid terms changed them, in order: what each body's traction walks,
  // rather than every unknown once per body.
  Array<int64_t> exchanged;
  bool solved = false;  // the last applyViscosity solved and recorded solidChange
};

// liquidPhi: nullptr for smoke (every cell is fluid), else the liquid level set (free_surface.h).
// kinematicViscosity in m^2/s, >= 0; dt > 0.
Status applyViscosity(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions,
                      const double* liquidPhi, double kinematicViscosity, double dt, const Deadline& deadline,
                      const ViscositySettings& settings, ViscosityWorkspace& work, ViscosityStats* stats);

// What the solids gave the fluid in the last applyViscosity, if it solved and recorded it: visit(axis, face,
// velocity change, coupling) for each fluid face whose solid terms changed it. The momentum of
// face f changed by rho h^3 times it, so the solids took the opposite: a body's viscous
// traction (fluid/solids/viscous_traction.h); `coupling` is that change per unit of the solids'
// velocity (ViscosityWorkspace::solidCoupling).
void forEachSolidExchange(const MacGrid& grid, const ViscosityWorkspace& work,
                          const std::function<void(int, const Eigen::Vector3i&, double, double)>& visit);

}  // namespace vp
