// A tilted jelly landing on the ground with each preconditioner: the solve must converge in
// every step. The contact active-set passes change which nodes are constrained (lift-off
// releases, sticking contacts turn sliding) and then re-solve; the multigrids carry the
// constraint filters in their smoothers and coarse spaces, so they must be rebuilt with the
// new filters. With stale filters the re-solve stalled at a relative residual near 1 (first
// seen with the voxelized assimp-testmodels duck in the sample host's scene).
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/box_tet_mesh.h"
#include "world.h"

namespace vp {
namespace {

struct LandingRun {
  int worstStep = -1;
  double worstResidual = 0.0;
  int contactSteps = 0;  // steps that ended with contacts: the landing was exercised
};

LandingRun landTiltedJelly(Preconditioner preconditioner, int degree) {
  WorldConfig config;
  config.workerCount = 2;
  config.frameBudgetMs = 0.0;  // no budget cuts: a stalled solve shows in its residual
  std::unique_ptr<World> world;
  EXPECT_EQ(World::create(config, &world), Status::Ok) << lastError();
  ColliderDesc ground;
  ground.shape.type = ShapeType::Plane;
  ground.friction = 0.8;
  ColliderHandle groundHandle;
  EXPECT_EQ(world->createCollider(ground, &groundHandle), Status::Ok) << lastError();

  // The sample scene's jelly material and solver settings, on a small tilted box.
  DeformableDesc d;
  d.degree = degree;
  d.mesh = makeBoxTetMesh({4, 4, 4}, Vec3::Constant(0.5), Vec3::Constant(-0.25));
  d.pose.position = Vec3(0, 0.6, 0);
  d.pose.rotation = Quat(Eigen::AngleAxisd(25.0 * M_PI / 180.0, Vec3(1, 0, 1).normalized()));
  d.material.youngsModulus = 2e5;
  d.material.poissonRatio = 0.4;
  d.material.density = 1100;
  d.material.stiffnessDamping = 0.01;
  d.material.friction = 0.8;
  d.solver.tolerance = 1e-3;
  d.solver.maxIterations = 100;
  d.solver.preconditioner = preconditioner;
  DeformableHandle jelly;
  EXPECT_EQ(world->createDeformable(std::move(d), &jelly), Status::Ok) << lastError();
  EXPECT_EQ(world->deformable(jelly)->preconditioner(), preconditioner);

  LandingRun run;
  for (int step = 0; step < 90; ++step) {
    EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok) << lastError();
    const ActorStats& stats = world->lastStats().actors.at(1);
    EXPECT_FALSE(stats.diverged) << "step " << step;
    const double residual = stats.phase(Phase::Solve).residual;
    if (residual > run.worstResidual) run.worstResidual = residual, run.worstStep = step;
    if (!world->deformable(jelly)->contacts().empty()) ++run.contactSteps;
  }
  return run;
}

void expectConvergedThroughLanding(Preconditioner preconditioner, int degree) {
  const LandingRun run = landTiltedJelly(preconditioner, degree);
  EXPECT_GT(run.contactSteps, 30) << "the jelly never settled on the ground";
  EXPECT_LE(run.worstResidual, 1e-3) << "worst relative residual at step " << run.worstStep;
}

TEST(DeformableContactSolve, AggregationMultigridConvergesWhileContactsChange) {
  expectConvergedThroughLanding(Preconditioner::Multigrid, 1);
}

TEST(DeformableContactSolve, PMultigridConvergesWhileContactsChange) {
  expectConvergedThroughLanding(Preconditioner::PMultigrid, 2);
}

// The reference: block-Jacobi is not filtered, so it never depended on the filters.
TEST(DeformableContactSolve, BlockJacobiConvergesWhileContactsChange) {
  expectConvergedThroughLanding(Preconditioner::BlockJacobi, 1);
}

}  // namespace
}  // namespace vp
