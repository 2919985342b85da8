#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstring>

#include "linalg/conjugate_gradient.h"

namespace vp {
namespace {

// 1D Laplacian plus a shift: SPD with a condition number that needs many CG iterations.
struct Laplacian {
  int64_t n;
  double shift;
  void apply(const double* x, double* y) const {
    for (int64_t i = 0; i < n; ++i)
      y[i] = (2.0 + shift) * x[i] - (i > 0 ? x[i - 1] : 0.0) - (i + 1 < n ? x[i + 1] : 0.0);
  }
  LinearSystem system() const {
    LinearSystem s;
    s.size = n;
    s.apply = [this](const double* x, double* y) { apply(x, y); };
    return s;
  }
};

TEST(ConjugateGradient, SolvesAnSpdSystemToTolerance) {
  Laplacian A{200, 0.01};
  std::vector<double> b(200), x(200, 0.0), Ax(200);
  for (int i = 0; i < 200; ++i) b[i] = std::sin(0.1 * i) + 0.5;
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  CgWorkspace work;
  CgSettings settings{1e-10, 1000};
  CgResult r = solveConjugateGradient(*tasks, A.system(), b.data(), x.data(), settings, Deadline(), work);
  ASSERT_TRUE(r.converged);
  EXPECT_FALSE(r.budgetCut);
  EXPECT_LE(r.iterations, 200);  // exact arithmetic needs at most n
  A.apply(x.data(), Ax.data());
  double err = 0, bn = 0;
  for (int i = 0; i < 200; ++i) err += (Ax[i] - b[i]) * (Ax[i] - b[i]), bn += b[i] * b[i];
  EXPECT_LT(std::sqrt(err / bn), 1e-9);
}

TEST(ConjugateGradient, FilterKeepsConstrainedValues) {
  Laplacian A{50, 0.0};
  std::vector<double> b(50, 1.0), x(50, 0.0);
  x[0] = 3.0;  // pinned values chosen by the caller
  x[49] = -2.0;
  LinearSystem sys = A.system();
  sys.filter = [](double* v) { v[0] = v[49] = 0.0; };
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  CgWorkspace work;
  CgResult r = solveConjugateGradient(*tasks, sys, b.data(), x.data(), CgSettings{1e-12, 500}, Deadline(), work);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(x[0], 3.0);
  EXPECT_EQ(x[49], -2.0);
  // Interior rows satisfy the equations with the pinned values as boundary data.
  std::vector<double> Ax(50);
  A.apply(x.data(), Ax.data());
  for (int i = 1; i < 49; ++i) EXPECT_NEAR(Ax[i], 1.0, 1e-9);
}

struct TickingClock {
  double t = 0.0;
  static double now(void* self) {
    auto* c = static_cast<TickingClock*>(self);
    c->t += 1e-3;  // 1 ms per query
    return c->t;
  }
};

TEST(ConjugateGradient, StopsAtTheDeadlineWithItsBestIterateAndWarmStarts) {
  Laplacian A{400, 1e-4};
  std::vector<double> b(400, 1.0), x(400, 0.0);
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  CgWorkspace work;
  TickingClock clock;
  CgSettings settings{1e-10, 10000};
  // Budget 10.5 ms at 1 ms per clock query: creating the deadline reads t = 1 ms (it ends at
  // 11.5 ms) and each iteration reads the clock once before it runs (t = 2 .. 11 pass,
  // t = 12 expires), so exactly 10 iterations run.
  Deadline deadline(Clock{&TickingClock::now, &clock}, 10.5);
  CgResult first = solveConjugateGradient(*tasks, A.system(), b.data(), x.data(), settings, deadline, work);
  EXPECT_TRUE(first.budgetCut);
  EXPECT_FALSE(first.converged);
  EXPECT_EQ(first.iterations, 10);
  // Warm start: every following frame continues from the last iterate, so the residual at
  // the end of each frame keeps falling and the solve converges within a few frames.
  double previous = first.relativeResidual;
  CgResult next;
  int frames = 0;
  for (; frames < 20 && !next.converged; ++frames) {
    Deadline d(Clock{&TickingClock::now, &clock}, 150.5);
    next = solveConjugateGradient(*tasks, A.system(), b.data(), x.data(), settings, d, work);
    EXPECT_LT(next.relativeResidual, previous) << "frame " << frames;
    previous = next.relativeResidual;
  }
  EXPECT_TRUE(next.converged);
  EXPECT_LE(frames, 10);
  // A cold start with the same per-frame budget is back at the first frame's residual.
  std::vector<double> cold(400, 0.0);
  Deadline d(Clock{&TickingClock::now, &clock}, 10.5);
  CgResult coldFirst = solveConjugateGradient(*tasks, A.system(), b.data(), cold.data(), settings, d, work);
  EXPECT_DOUBLE_EQ(coldFirst.relativeResidual, first.relativeResidual);
}

TEST(ConjugateGradient, ResultsAreBitwiseEqualForAnyWorkerCount) {
  const int64_t n = 50000;
  Laplacian A{n, 0.05};
  std::vector<double> b(n);
  for (int64_t i = 0; i < n; ++i) b[i] = std::cos(0.001 * i * i);
  std::vector<double> reference;
  for (int workers : {1, 2, 3}) {
    auto tasks = TaskSystem::create(TaskHooks{}, workers);
    std::vector<double> x(n, 0.0);
    CgWorkspace work;
    solveConjugateGradient(*tasks, A.system(), b.data(), x.data(), CgSettings{1e-8, 60}, Deadline(), work);
    if (reference.empty()) reference = x;
    else EXPECT_EQ(std::memcmp(reference.data(), x.data(), n * sizeof(double)), 0) << workers;
  }
}

}  // namespace
}  // namespace vp
