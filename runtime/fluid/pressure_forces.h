// Pressure force and torque of a fluid on one collider: the discrete adjoint of the way the
// collider's velocity enters the cut-cell divergence.
//
// A rigid velocity V(x) changes the net outflow of cell c by sum_f +-(1 - A_f) V_a(x_f) h^2
// (+ on the high face of each axis; the covered part of face f carries the solid's normal
// velocity). The power of the fluid on the body is then sum_c p_c * that, so
//     F   = sum_c sum_f +- p_c,f c_f h^2 e_a,
//     tau = sum_c sum_f +- p_c,f c_f h^2 (x_f - centre) x e_a,
// with c_f the part of face f this collider covers. p_c,f is the pressure of fluid cell c
// extrapolated linearly to the face from c and the cell beyond it (when that one is fluid
// too): with the cell-centre value itself, a submerged body of height H would feel the
// hydrostatic difference over H + h instead of H, a first-order error that makes light
// bodies float visibly too high on coarse grids.
#pragma once

#include "collide/face_coverage.h"
#include "core/math_types.h"
#include "fluid/cut_cell_poisson.h"
#include "fluid/mac_grid.h"

namespace vp {

struct PressureLoad {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();  // about `centre`
};

PressureLoad pressureLoadOnCollider(const MacGrid& grid, const CutCellPoisson& op, const double* pressure,
                                    const PreparedCollider& collider, const Vec3& centre);

}  // namespace vp
