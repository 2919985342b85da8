// The aggregation multigrid preconditioner on a real deformable system matrix.
#include <gtest/gtest.h>

#include <random>

#include "deform/deformable_body.h"
#include "deform_test_util.h"
#include "geometry/box_tet_mesh.h"
#include "linalg/aggregation_multigrid.h"

namespace vp {
namespace {

// Builds a clamped beam's step matrix (via one step of the actor) and its multigrid.
struct BeamSystem {
  std::unique_ptr<DeformableBody> body;
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  AggregationMultigrid mg;
  std::vector<double> filters;

  explicit BeamSystem(int n) {
    DeformableDesc d;
    d.mesh = makeBoxTetMesh({4 * n, n, n}, Vec3(4, 1, 1), Vec3::Zero());
    d.material.youngsModulus = 1e8;
    d.solver.preconditioner = Preconditioner::BlockJacobi;  // the test drives its own multigrid
    EXPECT_EQ(DeformableBody::create(d, &body), Status::Ok);
    deform_test::pinNodesAtX(*body, 0.0);
    DeformableStepInput in;
    in.tasks = tasks.get();
    ActorStats stats;
    body->step(in, &stats);
    filters.assign(9 * static_cast<size_t>(body->nodeCount()), 0.0);
    for (int32_t i = 0; i < body->nodeCount(); ++i)
      if (!body->pinned(i)) filters[9 * i] = filters[9 * i + 4] = filters[9 * i + 8] = 1.0;
    mg.build(body->stepMatrix());
    mg.update(*tasks, body->stepMatrix(), body->positions().data(), filters.data());
  }
  std::vector<double> randomFree(std::mt19937& rng) {
    std::normal_distribution<double> g;
    std::vector<double> v(3 * static_cast<size_t>(body->nodeCount()));
    for (size_t i = 0; i < v.size(); ++i) v[i] = body->pinned(static_cast<int32_t>(i / 3)) ? 0.0 : g(rng);
    return v;
  }
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

TEST(AggregationMultigrid, VCycleIsSymmetricAndPositive) {
  BeamSystem sys(6);
  EXPECT_GE(sys.mg.levelCount(), 3);
  std::mt19937 rng(2);
  for (int trial = 0; trial < 5; ++trial) {
    const std::vector<double> x = sys.randomFree(rng), y = sys.randomFree(rng);
    std::vector<double> Mx(x.size()), My(y.size());
    sys.mg.apply(*sys.tasks, x.data(), Mx.data());
    sys.mg.apply(*sys.tasks, y.data(), My.data());
    // x·My = y·Mx to round-off (relative to the size of the products).
    const double a = dot(x, My), b = dot(y, Mx);
    EXPECT_NEAR(a, b, 1e-10 * (std::abs(a) + std::abs(b) + dot(x, Mx)));
    EXPECT_GT(dot(x, Mx), 0.0);
  }
}

// The point of multigrid: once the hierarchy has its full depth (three levels from 6x refinement
// on; with two the coarse solve is exact and converges even faster) the CG iteration count
// barely grows when the mesh is refined
// (block-Jacobi's grows with the square root of the condition number, ~2x per refinement).
TEST(AggregationMultigrid, IterationsStayFlatUnderRefinement) {
  auto iterations = [](int n, Preconditioner pc) {
    DeformableDesc d;
    d.mesh = makeBoxTetMesh({4 * n, n, n}, Vec3(4, 1, 1), Vec3::Zero());
    d.material.youngsModulus = 1e8;
    d.solver.tolerance = 1e-6;
    d.solver.maxIterations = 5000;
    d.solver.preconditioner = pc;
    std::unique_ptr<DeformableBody> body;
    EXPECT_EQ(DeformableBody::create(d, &body), Status::Ok);
    deform_test::pinNodesAtX(*body, 0.0);
    auto tasks = TaskSystem::create(TaskHooks{}, 2);
    DeformableStepInput in;
    in.tasks = tasks.get();
    in.gravity = Vec3(0, -9.81, 0);
    ActorStats stats;
    body->step(in, &stats);
    EXPECT_LE(stats.phase(Phase::Solve).residual, 1e-6);
    return stats.phase(Phase::Solve).iterations;
  };
  const int coarse = iterations(6, Preconditioner::Multigrid), fine = iterations(12, Preconditioner::Multigrid);
  const int jacobiCoarse = iterations(6, Preconditioner::BlockJacobi), jacobiFine = iterations(12, Preconditioner::BlockJacobi);
  EXPECT_LE(fine, 1.3 * coarse + 2) << coarse << " -> " << fine;
  EXPECT_LT(3 * fine, jacobiFine) << "multigrid " << fine << " vs block-Jacobi " << jacobiFine;
  EXPECT_GT(jacobiFine, 1.5 * jacobiCoarse);  // the baseline really does degrade
}

// A mesh no larger than the coarsest level still gets a coarse level: with none, the cycle had
// no coarsest system to solve and returned nothing (CG stalled at a relative residual near 1).
TEST(AggregationMultigrid, AMeshNoLargerThanTheCoarsestLevelConverges) {
  DeformableDesc d;
  d.mesh = makeBoxTetMesh({3, 2, 3}, Vec3(0.3, 0.2, 0.3), Vec3::Zero());
  d.material.youngsModulus = 2e5;
  d.solver.tolerance = 1e-8;
  d.solver.maxIterations = 500;
  d.solver.preconditioner = Preconditioner::Multigrid;
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(d, &body), Status::Ok) << lastError();
  ASSERT_LE(body->nodeCount(), AggregationMultigrid::kMaxCoarsestNodes);
  deform_test::pinNodesAtX(*body, 0.0);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.tasks = tasks.get();
  in.dt = 0.1;
  in.gravity = Vec3(0, -9.81, 0);
  ActorStats stats;
  body->step(in, &stats);
  EXPECT_LE(stats.phase(Phase::Solve).residual, 1e-8);
  // Two levels: the coarse solve is exact on the aggregates' rigid modes, and the cycle needs
  // well under block-Jacobi's iterations on the same system (about twice the bound).
  EXPECT_LT(stats.phase(Phase::Solve).iterations, 30);
}

}  // namespace
}  // namespace vp
