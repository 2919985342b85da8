// Transport of MAC velocities and cell-centred scalars by the grid's velocity field.
//
// Semi-Lagrangian: each sample point (face or cell centre) is traced back through the
// velocity with the midpoint rule (RK2: x_mid = x - dt/2 u(x), x_back = x - dt u(x_mid)) and
// the old field is interpolated trilinearly there. Unconditionally stable, first order in
// space, and dissipative: it smooths every step.
//
// MacCormack (Selle, Fedkiw, Kim, Liu, Osher 2008): a forward semi-Lagrangian step phi^,
// a backward one from phi^ (tracing forward in time) phi~, and the corrected
// phi^ + (phi - phi~) / 2, which cancels the leading error term. The result is clamped to
// the range of the 8 old samples that the forward step interpolated, so the correction never
// creates new extrema (the scheme stays stable). Twice the cost, much less dissipation.
//
// Points traced out of the domain take the boundary's values (clamped sampling).
#pragma once

#include <vector>

#include "core/task_system.h"
#include "fluid/fluid_desc.h"
#include "fluid/mac_grid.h"

namespace vp {

// Scratch arrays, kept between steps so advection does not allocate.
struct AdvectionWorkspace {
  std::vector<double> advected[3];  // new velocity, per axis
  std::vector<double> forward, rangeLo, rangeHi;
  std::vector<Eigen::Vector3d> cellTrace;  // per cell: where its centre came from
};

// Replaces grid.velocity by itself advected over dt.
void advectVelocity(TaskSystem& tasks, MacGrid& grid, double dt, AdvectionScheme scheme, AdvectionWorkspace& work);

// Advects cell-centred scalars (each cellCount() values, cell order) by grid.velocity over dt.
// All fields share the traced points, so pass them together.
void advectCellScalars(TaskSystem& tasks, const MacGrid& grid, double dt, AdvectionScheme scheme,
                       std::vector<double>* const* fields, int fieldCount, AdvectionWorkspace& work);

}  // namespace vp
