// The multigrid's grid transfers: the CPU's row loops (multigrid_transfer.cpp) against the
// per-value kernel bodies a device thread runs (gpu_kernels/transfer_kernels.h), bit for bit,
// on every level of scenes with walls, open sides, solids and a free surface, odd and even
// sizes; and R = P^T.
#include <gtest/gtest.h>

#include <vector>

#include "fluid/pressure/multigrid_smoother.h"
#include "fluid/pressure/multigrid_transfer.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/transfer_kernels.h"
#include "random_values.h"
#include "same_bits.h"

namespace vp {
namespace {

using testscene::PressureScene;
using testscene::PressureSceneKind;
using testscene::SceneSolver;

using testing_values::expectSameBits;
using testing_values::randomValues;

kernels::TransferDims dimsOf(const CutCellPoisson& fine, const CutCellPoisson& coarse) {
  return kernels::TransferDims{fine.grid.nx,   fine.grid.ny,   fine.grid.nz,
                               coarse.grid.nx, coarse.grid.ny, coarse.grid.nz};
}

// The restriction of r by the kernels, one value at a time: along x, y, then z, and 0 on the
// coarse cells that hold no unknown (what restrictResidual does after its z pass).
std::vector<float> restrictByKernels(const CutCellPoisson& fine, const CutCellPoisson& coarse,
                                     const TransferSides& sides, const float* scale, const std::vector<float>& r) {
  const kernels::TransferDims d = dimsOf(fine, coarse);
  std::vector<float> alongX(static_cast<size_t>(d.cx * d.ny * d.nz)), alongY(static_cast<size_t>(d.cx * d.cy * d.nz));
  std::vector<float> out(static_cast<size_t>(d.cx * d.cy * d.cz));
  for (int64_t row = 0; row < d.ny * d.nz; ++row)
    for (int64_t I = 0; I < d.cx; ++I)
      alongX[static_cast<size_t>(I + d.cx * row)] = kernels::restrictAlongX(
          kernels::AxisWeights(I, d.nx, d.cx, sides, 0), scale + d.nx * row, r.data() + d.nx * row);
  for (int64_t k = 0; k < d.nz; ++k)
    for (int64_t J = 0; J < d.cy; ++J)
      for (int64_t I = 0; I < d.cx; ++I)
        alongY[static_cast<size_t>(I + d.cx * (J + d.cy * k))] = kernels::restrictAlong(
            kernels::AxisWeights(J, d.ny, d.cy, sides, 1), alongX.data() + I + d.cx * d.ny * k, d.cx);
  for (int64_t K = 0; K < d.cz; ++K)
    for (int64_t J = 0; J < d.cy; ++J)
      for (int64_t I = 0; I < d.cx; ++I) {
        const size_t c = static_cast<size_t>(I + d.cx * (J + d.cy * K));
        out[c] = coarse.diagonal[c] > 0.0 ? kernels::restrictAlong(kernels::AxisWeights(K, d.nz, d.cz, sides, 2),
                                                                   alongY.data() + I + d.cx * J, d.cx * d.cy)
                                          : 0.0f;
      }
  return out;
}

void checkEveryLevel(PressureSceneKind kind, int n) {
  SCOPED_TRACE(std::string(testscene::sceneName(kind)) + " at " + std::to_string(n));
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  PressureScene scene;
  SceneSolver solver;
  ASSERT_EQ(testscene::makeSceneWithMultigrid(*tasks, kind, n, &scene, &solver), Status::Ok) << lastError();
  const PoissonMultigrid& mg = solver.mg;
  ASSERT_GE(mg.levelCount(), 2);
  for (int l = 0; l + 1 < mg.levelCount(); ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    const CutCellPoisson& fine = l == 0 ? scene.poisson : mg.coarse[static_cast<size_t>(l - 1)];
    const CutCellPoisson& coarse = mg.coarse[static_cast<size_t>(l)];
    const float* scale = mg.prolongScale[static_cast<size_t>(l)].data();
    const kernels::TransferDims d = dimsOf(fine, coarse);
    const std::vector<float> coarseX = randomValues<float>(static_cast<int64_t>(coarse.diagonal.size()), 10 + l);
    const std::vector<float> fineStart = randomValues<float>(static_cast<int64_t>(fine.diagonal.size()), 20 + l);

    std::vector<float> byRows = fineStart, byCells = fineStart;
    prolongateAdd(*tasks, fine, coarse, mg.sides, scale, coarseX.data(), byRows.data());
    for (int64_t k = 0; k < d.nz; ++k)
      for (int64_t j = 0; j < d.ny; ++j)
        for (int64_t i = 0; i < d.nx; ++i)
          kernels::prolongateCell(d, mg.sides, i, j, k, scale, coarseX.data(), byCells.data());
    expectSameBits(byCells, byRows, "fine x + P coarse x");
    EXPECT_NE(byRows, fineStart);

    const PoissonCoefficients<float>& op = mg.single[static_cast<size_t>(l)];
    const std::vector<float> b = randomValues<float>(static_cast<int64_t>(fine.diagonal.size()), 30 + l);
    const std::vector<float> x = randomValues<float>(static_cast<int64_t>(fine.diagonal.size()), 40 + l);
    std::vector<float> residual(fine.diagonal.size());
    computeResidual(*tasks, op, b.data(), x.data(), residual.data());
    std::vector<float> restricted(coarse.diagonal.size(), 7.0f);
    Array<float> scratch;
    restrictResidual(*tasks, fine, coarse, mg.sides, scale, LevelResidual<float>{&op, b.data(), x.data()},
                     restricted.data(), &scratch);
    expectSameBits(restrictByKernels(fine, coarse, mg.sides, scale, residual), restricted, "P^T (b - A x)");

    // R = P^T: <R r, y> = <r, P y> for y = 0 on the coarse cells that hold no unknown (as the
    // V-cycle keeps them), to rounding in single precision.
    std::vector<float> y = coarseX;
    for (size_t c = 0; c < y.size(); ++c)
      if (!(coarse.diagonal[c] > 0.0)) y[c] = 0.0f;
    std::vector<float> py(fine.diagonal.size(), 0.0f);
    prolongateAdd(*tasks, fine, coarse, mg.sides, scale, y.data(), py.data());
    double left = 0.0, right = 0.0, size = 0.0;
    for (size_t c = 0; c < restricted.size(); ++c) left += double(restricted[c]) * y[c];
    for (size_t c = 0; c < py.size(); ++c) {
      right += double(residual[c]) * py[c];
      size += std::abs(double(residual[c]) * py[c]);
    }
    EXPECT_NEAR(left, right, 1e-5 * size);
  }
}

TEST(FluidMultigridTransfer, RowLoopsEqualTheKernelBodiesOnEveryLevel) {
  checkEveryLevel(PressureSceneKind::SmokeSphere, 24);
  checkEveryLevel(PressureSceneKind::SmokeSphere, 21);
  checkEveryLevel(PressureSceneKind::TankPlateSphere, 19);
  checkEveryLevel(PressureSceneKind::LiquidTank, 22);
}

}  // namespace
}  // namespace vp
