// The CUDA block solver against the CPU on the same beam system (ctest label gpu). Without a
// device every test is skipped by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "beam_step_system.h"
#include "gpu_kernels/device_query.h"
#include "../unit/random_values.h"

namespace vp::gpu_test {
namespace {

constexpr double kTolerance = 1e-8;

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
  double trueRelativeResidual(const std::vector<double>& x, const NodeConstraints& constraints) const {
    std::vector<double> r(x.size()), fb(sys->rhs);
    sys->matrix().multiply(*sys->tasks, x.data(), r.data());
    for (size_t i = 0; i < x.size(); ++i) r[i] = sys->rhs[i] - r[i];
    constraints.filter(*sys->tasks, r.data());
    constraints.filter(*sys->tasks, fb.data());
    double rr = 0, bb = 0;
    for (size_t i = 0; i < x.size(); ++i) rr += r[i] * r[i], bb += fb[i] * fb[i];
    return std::sqrt(rr / bb);
  }

  CgResult cpuSolve(const std::vector<double>& b, std::vector<double>* x, double tolerance, int maxIterations) const {
    CgWorkspace work;
    return solveConjugateGradient(*sys->tasks, cpuLinearSystem(*sys), b.data(), x->data(),
                                  CgSettings{tolerance, maxIterations}, Deadline(), work);
  }

  BeamStepSystem* sys = nullptr;
  std::unique_ptr<gpu::DeviceBlockSystem> device;
};

std::vector<double> wave(size_t n, double frequency) {
  std::vector<double> x(n);
  for (size_t i = 0; i < n; ++i) x[i] = std::sin(frequency * double(i)) + 0.1;
  return x;
}

// Device and CPU sum the same products in the same order; only the device's fused
// multiply-adds round differently. Each result is within gamma_n = n u sum |a_ij x_j| of the
// exact row (n terms, unit roundoff u), so the two differ by at most twice that.
void expectProductsWithinRounding(const BlockSparseMatrix<double>& a, const std::vector<double>& x,
                                  const std::vector<double>& cpu, const std::vector<double>& gpu) {
  const double u = std::numeric_limits<double>::epsilon() / 2;
  for (int32_t r = 0; r < a.blockRows; ++r)
    for (int i = 0; i < 3; ++i) {
      double magnitude = 0;
      const int terms = 3 * (a.rowStart[r + 1] - a.rowStart[r]);
      for (int32_t k = a.rowStart[r]; k < a.rowStart[r + 1]; ++k)
        for (int j = 0; j < 3; ++j)
          magnitude += std::abs(a.values[9 * size_t(k) + 3 * i + j] * x[3 * size_t(a.columns[k]) + j]);
      const size_t row = 3 * size_t(r) + i;
      EXPECT_LE(std::abs(gpu[row] - cpu[row]), 2 * terms * u * magnitude) << "row " << r;
    }
}

TEST_F(DeviceBlockSystemTest, BinBcsrAndBcsrProductsMatchTheCpuWithinRounding) {
  const std::vector<double> x = wave(size_t(sys->dofs()), 0.37);
  std::vector<double> cpu(x.size()), bin(x.size()), bcsr(x.size());
  sys->matrix().multiply(*sys->tasks, x.data(), cpu.data());
  std::string error;
  ASSERT_TRUE(device->multiply(x.data(), bin.data(), false, &error)) << error;
  ASSERT_TRUE(device->multiply(x.data(), bcsr.data(), true, &error)) << error;
  expectProductsWithinRounding(sys->matrix(), x, cpu, bin);
  expectProductsWithinRounding(sys->matrix(), x, cpu, bcsr);
}

// New values in the same pattern (a later step's matrix): the device multiplies with them.
TEST_F(DeviceBlockSystemTest, NewValuesReplaceTheOldOnesWithoutANewPattern) {
  BlockSparseMatrix<double> scaled = sys->matrix();
  for (size_t k = 0; k < scaled.values.size(); ++k) scaled.values[k] *= 1.0 + 0.5 * std::cos(double(k));
  BinBcsrMatrix<double> bin = sys->bin;
  refreshBinBcsrValues(scaled, &bin);
  std::string error;
  ASSERT_TRUE(device->setValues(bin.values.data(), bin.diagonal.data(), sys->inverseDiagonal.data(), &error)) << error;
  const std::vector<double> x = wave(size_t(sys->dofs()), 0.21);
  std::vector<double> cpu(x.size()), gpu(x.size());
  scaled.multiply(*sys->tasks, x.data(), cpu.data());
  ASSERT_TRUE(device->multiply(x.data(), gpu.data(), false, &error)) << error;
  expectProductsWithinRounding(scaled, x, cpu, gpu);
}

// Both device forms run the CPU's CG: the same Krylov iterates up to rounding, so they stop
// within an iteration or two of the CPU, and their answers satisfy the tolerance when the
// residual is recomputed on the CPU (the recurrence's drift at 1e-8 is far below it). Run with
// the clamped end fixed, then with every fifth free node also sliding on a contact plane.
TEST_F(DeviceBlockSystemTest, FusedAndUnfusedCgSolveTheBeamStepLikeTheCpu) {
  const NodeConstraints clampedOnly = sys->constraints;
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  NodeConstraints sliding = clampedOnly;
  for (int32_t i = 0; i < sys->matrix().blockRows; i += 5) {
    if (sliding.kind[i] != NodeConstraints::kFree) continue;
    Vec3 n = testing_values::randomVector(g, rng);
    n.normalize();
    sliding.kind[i] = NodeConstraints::kContact;
    for (int k = 0; k < 3; ++k) sliding.normal[3 * size_t(i) + k] = n[k];
  }
  for (const NodeConstraints* constraints : {&clampedOnly, static_cast<const NodeConstraints*>(&sliding)}) {
    SCOPED_TRACE(constraints == &sliding ? "sliding contacts" : "clamped only");
    sys->constraints = *constraints;
    std::string error;
    ASSERT_TRUE(device->setConstraints(constraints->kind.data(), constraints->normal.data(), &error)) << error;
    std::vector<double> cpuX(size_t(sys->dofs()), 0.0);
    const CgResult cpu = cpuSolve(sys->rhs, &cpuX, kTolerance, 5000);
    ASSERT_TRUE(cpu.converged);
    for (gpu::DeviceCgForm form : {gpu::DeviceCgForm::Fused, gpu::DeviceCgForm::Unfused}) {
      SCOPED_TRACE(form == gpu::DeviceCgForm::Fused ? "fused" : "unfused");
      std::vector<double> x(size_t(sys->dofs()), 0.0);
      gpu::DeviceCgResult result;
      ASSERT_TRUE(device->solve(sys->rhs.data(), x.data(), kTolerance, 5000, form, &result, &error)) << error;
      EXPECT_TRUE(result.converged);
      EXPECT_NEAR(result.iterations, cpu.iterations, 2);
      EXPECT_LE(trueRelativeResidual(x, *constraints), 2 * kTolerance);
      if (form == gpu::DeviceCgForm::Fused) {
        // Three launches per iteration, plus those issued before the host saw the stop flag.
        const int checks = gpu::DeviceBlockSystem::kStopCheckInterval;
        EXPECT_EQ(result.launches, 3 * ((result.iterations + checks - 1) / checks * checks));
      }
    }
  }
  sys->constraints = clampedOnly;
}

// A caller that stops the solve at its first look (a spent frame budget) gets the CPU's
// iterate after that many iterations, up to rounding.
TEST_F(DeviceBlockSystemTest, ACallerStopsTheSolveBetweenLaunchesWithTheIterateSoFar) {
  const int checks = gpu::DeviceBlockSystem::kStopCheckInterval;
  std::vector<double> cpuX(size_t(sys->dofs()), 0.0);
  const CgResult cpu = cpuSolve(sys->rhs, &cpuX, kTolerance, checks);
  ASSERT_EQ(cpu.iterations, checks);
  gpu::DeviceCgControl stopAtOnce;
  int looks = 0;
  stopAtOnce.context = &looks;
  stopAtOnce.stop = [](void* context, int, double) { return ++*static_cast<int*>(context) >= 1; };
  std::vector<double> x(size_t(sys->dofs()), 0.0);
  gpu::DeviceCgResult result;
  std::string error;
  ASSERT_TRUE(device->solve(sys->rhs.data(), x.data(), kTolerance, 5000, gpu::DeviceCgForm::Fused, &result, &error,
                            stopAtOnce))
      << error;
  EXPECT_TRUE(result.stoppedByCaller);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, checks);
  EXPECT_NEAR(result.relativeResidual, cpu.relativeResidual, 1e-9 * cpu.relativeResidual);
  double difference = 0, scale = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    difference = std::max(difference, std::abs(x[i] - cpuX[i]));
    scale = std::max(scale, std::abs(cpuX[i]));
  }
  // Eight iterations' rounding, far below the iterates' own change per iteration.
  EXPECT_LE(difference, 1e-10 * scale);
}

// Nothing drives the system: the answer keeps only the constrained part of the start, as the
// CPU's CG does.
TEST_F(DeviceBlockSystemTest, WithoutAFilteredRightHandSideTheFreePartIsRemoved) {
  const std::vector<double> zero(size_t(sys->dofs()), 0.0);
  std::vector<double> cpuX = wave(size_t(sys->dofs()), 0.5), x = cpuX;
  const CgResult cpu = cpuSolve(zero, &cpuX, kTolerance, 100);
  gpu::DeviceCgResult result;
  std::string error;
  ASSERT_TRUE(device->solve(zero.data(), x.data(), kTolerance, 100, gpu::DeviceCgForm::Fused, &result, &error)) << error;
  EXPECT_TRUE(cpu.converged);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(x, cpuX);  // x - F x: a zero for a free component, the start's value for a fixed one
}

}  // namespace
}  // namespace vp::gpu_test
