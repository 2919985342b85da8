// One viscous step of a still fluid beside moving solids, recording what the solids gave it
// (ViscositySettings::recordSolidExchange), for the tests of the viscous traction: solved to
// 1e-12 so that the solve's residual does not count in a momentum balance.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/face_fraction_field.h"
#include "fluid/viscosity.h"

namespace vp {
namespace testutil {

inline void viscousStepFromRest(const FaceFractionField& field, double nu, double dt, MacGrid* grid,
                                ViscosityWorkspace* work) {
  grid->spec = field.grid;
  for (int a = 0; a < 3; ++a) grid->velocity[a].assign(field.open[a].size(), 0.0);
  ViscositySettings settings;
  settings.tolerance = 1e-12;
  settings.maxIterations = 1000;
  settings.recordSolidExchange = true;
  ViscosityStats stats;
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  ASSERT_EQ(applyViscosity(*tasks, *grid, field, nullptr, nu, dt, Deadline{}, settings, *work, &stats), Status::Ok);
}

}  // namespace testutil
}  // namespace vp
