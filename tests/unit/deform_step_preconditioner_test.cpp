// Auto's preconditioner on a mesh under kMultigridMinNodes, chosen per step
// (deform/step_preconditioner.h): block-Jacobi while an elastic wave crosses few node spacings
// in a step, the multigrid beyond kMultigridWaveCrossings. A hanging jelly (pinned along its
// top) stepped at a frame's dt and at a long step, as a body paced by a liquid steps.
#include <gtest/gtest.h>

#include "geometry/box_tet_mesh.h"
#include "world.h"

namespace vp {
namespace {

constexpr double kFrameDt = 1.0 / 60.0;
// On the jelly's 0.125 m cells a pressure wave crosses fewer than kMultigridWaveCrossings node
// spacings in a frame's dt and more in this step (DeformableBody::elasticWaveCrossings).
constexpr double kLongDt = 0.2;

struct HangingJelly {
  std::unique_ptr<World> world;
  DeformableHandle handle;

  HangingJelly(int degree, Preconditioner preconditioner) {
    WorldConfig config;
    config.workerCount = 2;
    config.frameBudgetMs = 0.0;  // every solve runs to its tolerance
    EXPECT_EQ(World::create(config, &world), Status::Ok) << lastError();
    const int cells = degree == 1 ? 4 : 2;
    DeformableDesc d;
    d.degree = degree;
    d.mesh = makeBoxTetMesh({cells, cells, cells}, Vec3::Constant(0.5), Vec3::Constant(-0.25));
    d.pose.position = Vec3(0, 1.0, 0);
    d.material.youngsModulus = 2e5;
    d.material.poissonRatio = 0.4;
    d.material.density = 1100;
    d.material.stiffnessDamping = 0.01;
    d.solver.tolerance = 1e-6;
    d.solver.maxIterations = 2000;
    d.solver.preconditioner = preconditioner;
    EXPECT_EQ(world->createDeformable(std::move(d), &handle), Status::Ok) << lastError();
    std::vector<int32_t> top;
    const Array<double>& x = body().positions();
    for (int32_t i = 0; i < body().nodeCount(); ++i)
      if (x[3 * i + 1] > 1.25 - 1e-9) top.push_back(i);
    EXPECT_EQ(body().setPinned(top.data(), static_cast<int64_t>(top.size()), true), Status::Ok) << lastError();
  }
  DeformableBody& body() { return *world->deformable(handle); }
  // One step of dt: the solve's iterations and relative residual.
  PhaseStats step(double dt) {
    EXPECT_EQ(world->step(dt), Status::Ok) << lastError();
    for (const ActorStats& a : world->lastStats().actors)
      if (a.kind == ActorKind::Deformable) return a.phase(Phase::Solve);
    ADD_FAILURE() << "no deformable in the step's stats";
    return PhaseStats{};
  }
};

TEST(AutoStepPreconditioner, ASmallLinearJellyTakesTheMultigridForALongStepOnly) {
  HangingJelly jelly(1, Preconditioner::Auto);
  ASSERT_LT(jelly.body().nodeCount(), kMultigridMinNodes);
  EXPECT_EQ(jelly.body().preconditioner(), Preconditioner::BlockJacobi);
  jelly.step(kFrameDt);
  EXPECT_EQ(jelly.body().preconditioner(), Preconditioner::BlockJacobi);
  jelly.step(kLongDt);
  EXPECT_EQ(jelly.body().preconditioner(), Preconditioner::Multigrid);
  jelly.step(kFrameDt);
  EXPECT_EQ(jelly.body().preconditioner(), Preconditioner::BlockJacobi);
}

TEST(AutoStepPreconditioner, ASmallQuadraticJellyKeepsBlockJacobi) {
  HangingJelly jelly(2, Preconditioner::Auto);
  ASSERT_LT(jelly.body().nodeCount(), kMultigridMinNodes);
  jelly.step(kLongDt);
  EXPECT_EQ(jelly.body().preconditioner(), Preconditioner::BlockJacobi);
}

TEST(AutoStepPreconditioner, AFixedChoiceStaysWhateverTheStep) {
  HangingJelly jelly(1, Preconditioner::BlockJacobi);
  jelly.step(kLongDt);
  EXPECT_EQ(jelly.body().preconditioner(), Preconditioner::BlockJacobi);
}

// What the switch is for: at the long step block-Jacobi needs many times the multigrid's
// iterations to the same tolerance, and both solve the same system (the same sag).
TEST(AutoStepPreconditioner, TheLongStepConvergesInFarFewerIterationsToTheSameState) {
  HangingJelly automatic(1, Preconditioner::Auto), blockJacobi(1, Preconditioner::BlockJacobi);
  automatic.step(kFrameDt);
  blockJacobi.step(kFrameDt);
  const PhaseStats a = automatic.step(kLongDt), b = blockJacobi.step(kLongDt);
  EXPECT_LE(a.residual, 1e-6);
  EXPECT_LE(b.residual, 1e-6);
  EXPECT_LT(2 * a.iterations, b.iterations) << a.iterations << " against " << b.iterations;
  const Array<double>& xa = automatic.body().positions();
  const Array<double>& xb = blockJacobi.body().positions();
  double largest = 0.0;
  for (size_t k = 0; k < xa.size(); ++k) largest = std::max(largest, std::abs(xa[k] - xb[k]));
  // Two solves to a relative residual of 1e-6 from the same state: velocities within about 1e-6
  // of their scale (centimetres per second here), times the step, with room for the condition.
  EXPECT_LT(largest, 1e-8);
}

}  // namespace
}  // namespace vp
