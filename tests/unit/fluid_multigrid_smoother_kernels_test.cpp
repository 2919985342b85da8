// The multigrid's smoothing and residual: the CPU's row loops (multigrid_smoother.cpp) against
// the per-cell kernel bodies a device thread runs (gpu_kernels/smoother_kernels.h), bit for bit,
// on every level of scenes with walls, open sides, solids and a free surface, odd and even
// sizes: a red-black sweep in both orders, a sweep from zero (the device clears x, then sweeps),
// and the residual.
#include <gtest/gtest.h>

#include <vector>

#include "fluid/pressure/multigrid_smoother.h"
#include "fluid/pressure/poisson_rows.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/smoother_kernels.h"
#include "random_values.h"
#include "same_bits.h"

namespace vp {
namespace {

using testscene::PressureScene;
using testscene::PressureSceneKind;
using testscene::SceneSolver;
using testing_values::expectSameBits;
using testing_values::randomValues;

// One sweep by the kernel bodies: every thread of the first colour, then of the second.
void sweepByCells(const kernels::PoissonStencil<float>& s, const float* b, float* x, bool reverse) {
  const int64_t threads = kernels::colourThreads(s);
  for (int half = 0; half < 2; ++half) {
    const int colour = reverse ? 1 - half : half;
    for (int64_t t = 0; t < threads; ++t) {
      int64_t cell;
      if (kernels::colourCell(s, t, colour, &cell)) kernels::gaussSeidelCell(s, cell, b, x);
    }
  }
}

void checkEveryLevel(PressureSceneKind kind, int n) {
  SCOPED_TRACE(std::string(testscene::sceneName(kind)) + " at " + std::to_string(n));
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  PressureScene scene;
  SceneSolver solver;
  ASSERT_EQ(testscene::makeSceneWithMultigrid(*tasks, kind, n, &scene, &solver), Status::Ok) << lastError();
  const PoissonMultigrid& mg = solver.mg;
  ASSERT_GE(mg.levelCount(), 2);
  for (int l = 0; l < mg.levelCount(); ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    const PoissonCoefficients<float>& op = mg.single[static_cast<size_t>(l)];
    const poisson_rows::Stencil<float> s(op);
    const int64_t cells = static_cast<int64_t>(op.diagonal.size());
    const std::vector<float> b = randomValues<float>(cells, 50 + l);
    std::vector<float> start = randomValues<float>(cells, 60 + l);
    for (int64_t c = 0; c < cells; ++c)
      if (!(op.diagonal[static_cast<size_t>(c)] > 0.0f)) start[static_cast<size_t>(c)] = 0.0f;  // as the V-cycle keeps them

    for (bool reverse : {false, true}) {
      std::vector<float> byRows = start, byCells = start;
      smoothRedBlack(*tasks, op, b.data(), byRows.data(), reverse);
      sweepByCells(s, b.data(), byCells.data(), reverse);
      expectSameBits(byCells, byRows, reverse ? "black-red sweep" : "red-black sweep");
      EXPECT_NE(byRows, start);
    }

    std::vector<float> fromZero = randomValues<float>(cells, 70 + l), cleared(static_cast<size_t>(cells), 0.0f);
    smoothRedBlack(*tasks, op, b.data(), fromZero.data(), false, true);
    sweepByCells(s, b.data(), cleared.data(), false);
    expectSameBits(cleared, fromZero, "sweep from zero");

    std::vector<float> residual(static_cast<size_t>(cells)), byCells(static_cast<size_t>(cells));
    computeResidual(*tasks, op, b.data(), start.data(), residual.data());
    for (int64_t c = 0; c < cells; ++c)
      byCells[static_cast<size_t>(c)] = kernels::residualCell(s, c, b.data(), start.data());
    expectSameBits(byCells, residual, "b - A x");
  }
}

TEST(FluidMultigridSmoother, RowLoopsEqualTheKernelBodiesOnEveryLevel) {
  checkEveryLevel(PressureSceneKind::SmokeSphere, 24);
  checkEveryLevel(PressureSceneKind::SmokeSphere, 21);
  checkEveryLevel(PressureSceneKind::ClosedTank, 20);
  checkEveryLevel(PressureSceneKind::LiquidTank, 23);
}

}  // namespace
}  // namespace vp
