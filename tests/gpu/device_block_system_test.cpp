// The CUDA block solver against the CPU on the same beam system (ctest label gpu). Without a
// device every test is skipped by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "beam_step_system.h"
#include "gpu_kernels/device_query.h"
#include "linalg/conjugate_gradient.h"

namespace vp::gpu_test {
namespace {

class DeviceBlockSystemTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (gpu::cudaDeviceCount() == 0) GTEST_SKIP() << "no CUDA device on this machine";
    static BeamStepSystem* shared = [] {
      auto* s = new BeamStepSystem;
      bench::BeamCells cells;
      cells.x = 16, cells.y = 4, cells.z = 4;  // 1536 tets: 425 nodes, a padded last bin
      return makeBeamStepSystem(cells, 1, s) ? s : nullptr;
    }();
    ASSERT_NE(shared, nullptr) << lastError();
    sys = shared;
    std::string error;
    device = gpu::DeviceBlockSystem::create(sys->host(true), &error);
    ASSERT_NE(device, nullptr) << error;
  }

  // |F (b - A x)| / |F b| computed on the CPU.
  double trueRelativeResidual(const std::vector<double>& x) const {
    std::vector<double> ax(x.size());
    sys->matrix().multiply(*sys->tasks, x.data(), ax.data());
    double rr = 0, bb = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      const double r = sys->freeDofs[i] * (sys->rhs[i] - ax[i]);
      rr += r * r;
      bb += sys->freeDofs[i] * sys->rhs[i] * sys->rhs[i];
    }
    return std::sqrt(rr / bb);
  }

  BeamStepSystem* sys = nullptr;
  std::unique_ptr<gpu::DeviceBlockSystem> device;
};

// Device and CPU sum the same products in the same order; only the device's fused
// multiply-adds round differently. Each result is within gamma_n = n u sum |a_ij x_j| of the
// exact row (n terms, unit roundoff u), so the two differ by at most twice that.
TEST_F(DeviceBlockSystemTest, BinBcsrAndBcsrProductsMatchTheCpuWithinRounding) {
  const BlockSparseMatrix<double>& a = sys->matrix();
  std::vector<double> x(static_cast<size_t>(sys->dofs()));
  for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.37 * double(i)) + 0.1;
  std::vector<double> cpu(x.size()), bin(x.size()), bcsr(x.size());
  a.multiply(*sys->tasks, x.data(), cpu.data());
  std::string error;
  ASSERT_TRUE(device->multiply(x.data(), bin.data(), false, &error)) << error;
  ASSERT_TRUE(device->multiply(x.data(), bcsr.data(), true, &error)) << error;
  const double u = std::numeric_limits<double>::epsilon() / 2;
  for (int32_t r = 0; r < a.blockRows; ++r)
    for (int i = 0; i < 3; ++i) {
      double magnitude = 0;
      const int terms = 3 * (a.rowStart[r + 1] - a.rowStart[r]);
      for (int32_t k = a.rowStart[r]; k < a.rowStart[r + 1]; ++k)
        for (int j = 0; j < 3; ++j)
          magnitude += std::abs(a.values[9 * size_t(k) + 3 * i + j] * x[3 * size_t(a.columns[k]) + j]);
      const double bound = 2 * terms * u * magnitude;
      const size_t row = 3 * size_t(r) + i;
      EXPECT_LE(std::abs(bin[row] - cpu[row]), bound) << "row " << r;
      EXPECT_LE(std::abs(bcsr[row] - cpu[row]), bound) << "row " << r;
    }
}

// Both device forms run the CPU's CG: the same Krylov iterates up to rounding, so they stop
// within an iteration or two of the CPU, and their answers satisfy the tolerance when the
// residual is recomputed on the CPU (the recurrence's drift at 1e-8 is far below it).
TEST_F(DeviceBlockSystemTest, FusedAndUnfusedCgSolveTheBeamStepLikeTheCpu) {
  constexpr double kTolerance = 1e-8;
  const int64_t n = sys->dofs();
  LinearSystem cpuSystem;
  cpuSystem.size = n;
  cpuSystem.apply = [&](const double* x, double* y) { sys->matrix().multiply(*sys->tasks, x, y); };
  cpuSystem.precondition = [&](const double* r, double* z) {
    for (int32_t row = 0; row < sys->matrix().blockRows; ++row)
      kernels::blockJacobiRow(row, sys->inverseDiagonal.data(), r, z);
  };
  cpuSystem.filter = [&](double* v) {
    for (int64_t i = 0; i < n; ++i) v[i] *= sys->freeDofs[size_t(i)];
  };
  std::vector<double> cpuX(size_t(n), 0.0);
  CgWorkspace work;
  const CgResult cpu = solveConjugateGradient(*sys->tasks, cpuSystem, sys->rhs.data(), cpuX.data(),
                                              CgSettings{kTolerance, 5000}, Deadline(), work);
  ASSERT_TRUE(cpu.converged);
  for (gpu::DeviceCgForm form : {gpu::DeviceCgForm::Fused, gpu::DeviceCgForm::Unfused}) {
    SCOPED_TRACE(form == gpu::DeviceCgForm::Fused ? "fused" : "unfused");
    std::vector<double> x(size_t(n), 0.0);
    gpu::DeviceCgResult result;
    std::string error;
    ASSERT_TRUE(device->solve(sys->rhs.data(), x.data(), kTolerance, 5000, form, &result, &error)) << error;
    EXPECT_TRUE(result.converged);
    EXPECT_NEAR(result.iterations, cpu.iterations, 2);
    EXPECT_LE(trueRelativeResidual(x), 2 * kTolerance);
    if (form == gpu::DeviceCgForm::Fused) {
      // Three launches per iteration, plus those issued before the host saw the stop flag.
      const int checks = gpu::DeviceBlockSystem::kStopCheckInterval;
      EXPECT_EQ(result.launches, 3 * ((result.iterations + checks - 1) / checks * checks));
    }
  }
}

}  // namespace
}  // namespace vp::gpu_test
