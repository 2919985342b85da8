// What keeps a deformable's step sound: the energy guard (core/step_energy.h) restores a step
// whose mechanical energy rises beyond what gravity, the host's forces and the constraints put
// in, and not steps whose gain that work explains, however large; the contact passes release
// pulling contacts even when the frame's share ran out.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "collide/face_coverage.h"
#include "deform/deformable_body.h"
#include "core/step_energy.h"
#include "geometry/box_tet_mesh.h"
#include "../budget/tick_clock.h"

namespace vp {
namespace {

TEST(StepEnergyGuard, AGainTheWorkExplainsIsNotABlowUp) {
  StepEnergy e;
  e.kineticStart = 1.0, e.elasticStart = 2.0;
  e.gravityWork = 50.0, e.appliedWork = 40.0;
  e.kineticEnd = 60.0, e.elasticEnd = 33.0;  // exactly start + work
  EXPECT_DOUBLE_EQ(StepEnergyGuard::unexplainedGain(e), 0.0);
  EXPECT_FALSE(StepEnergyGuard::blewUp(e, 1.0));
}

// Work known only by its bound (a moving boundary's, a fluid's sources) explains a gain up to
// the bound and adds to the energy the step had to work with.
TEST(StepEnergyGuard, BoundedWorkIsExplainedAndAvailable) {
  StepEnergy e;
  e.kineticStart = 1.0;
  e.boundedWork = 10.0;
  e.kineticEnd = 11.0;
  EXPECT_DOUBLE_EQ(StepEnergyGuard::unexplainedGain(e), 0.0);
  EXPECT_DOUBLE_EQ(StepEnergyGuard::available(e), 11.0);
  e.kineticEnd = 11.0 + StepEnergyGuard::kGrowthFactor * 11.0 + 1.0;  // beyond bound and factor
  EXPECT_TRUE(StepEnergyGuard::blewUp(e, 1.0));
}

TEST(StepEnergyGuard, AnUnexplainedGainAboveTheFactorIsABlowUp) {
  StepEnergy e;
  e.kineticStart = 10.0, e.elasticStart = 10.0;  // 20 J to work with, no work done
  const double allowed = StepEnergyGuard::kGrowthFactor * 20.0;
  const double noise = 0.5 * 1.0 * StepEnergyGuard::kNoiseSpeed * StepEnergyGuard::kNoiseSpeed;
  e.kineticEnd = 20.0 + allowed;  // just inside
  EXPECT_FALSE(StepEnergyGuard::blewUp(e, 1.0));
  e.kineticEnd = 20.0 + allowed + 2.0 * noise;  // just beyond
  EXPECT_TRUE(StepEnergyGuard::blewUp(e, 1.0));
  e.kineticEnd = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(StepEnergyGuard::blewUp(e, 1.0));
}

TEST(StepEnergyGuard, RoundingAtRestIsNotABlowUp) {
  StepEnergy e;  // nothing to work with: only the noise floor separates rounding from a blow-up
  e.kineticEnd = 1e-12;
  EXPECT_FALSE(StepEnergyGuard::blewUp(e, 1.0));
}

// A 2 m bar of soft rubber, clamped at x = 0, in gravity.
std::unique_ptr<DeformableBody> clampedBar() {
  DeformableDesc desc;
  desc.mesh = makeBoxTetMesh({16, 3, 3}, Vec3(2.0, 0.25, 0.25), Vec3(0, -0.125, -0.125));
  desc.material.youngsModulus = 5e5;
  desc.material.density = 800.0;
  std::unique_ptr<DeformableBody> body;
  EXPECT_EQ(DeformableBody::create(std::move(desc), &body), Status::Ok) << lastError();
  std::vector<int32_t> clamped;
  for (int32_t i = 0; i < body->nodeCount(); ++i)
    if (body->restPositions()[3 * i] == 0.0) clamped.push_back(i);
  EXPECT_EQ(body->setPinned(clamped.data(), static_cast<int64_t>(clamped.size()), true), Status::Ok);
  return body;
}

// One backward-Euler step of a whole second from rest: linear theory sags the tip by metres,
// so the linearized step stretches the bar to several times its length. The corotated energy
// of that state is far beyond the work gravity did on it: the step blew up, although every
// speed is finite and below the speed guard's bound. The bar goes back to where it was.
TEST(DeformableEnergyGuard, AStepThatStretchesFarBeyondItsWorkIsRestored) {
  auto body = clampedBar();
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const Array<double> before = body->positions();
  DeformableStepInput in;
  in.tasks = tasks.get();
  in.gravity = Vec3(0, -9.81, 0);
  in.dt = 1.0;
  ActorStats stats;
  body->step(in, &stats);
  EXPECT_TRUE(stats.diverged);
  EXPECT_EQ(body->positions(), before);
  for (double v : body->velocities()) EXPECT_EQ(v, 0.0);
}

// The same bar at a game's time step sags under gravity: energy flows from gravity's work
// into kinetic and elastic energy and nothing is flagged.
TEST(DeformableEnergyGuard, AFallingBarAtAGameTimeStepIsNotFlagged) {
  auto body = clampedBar();
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.tasks = tasks.get();
  in.gravity = Vec3(0, -9.81, 0);
  for (int step = 0; step < 120; ++step) {
    ActorStats stats;
    body->step(in, &stats);
    ASSERT_FALSE(stats.diverged) << "step " << step;
  }
  EXPECT_GT(body->elasticEnergy(*tasks), 0.0);
}

// Energy the host puts in (forces, teleports that compress the body) is work or start energy,
// never a blow-up: a strong push and the release of a squashed body both step unflagged.
TEST(DeformableEnergyGuard, HostForcesAndElasticReleaseAreNotFlagged) {
  DeformableDesc desc;
  desc.mesh = makeBoxTetMesh({3, 3, 3}, Vec3(0.6, 0.6, 0.6), Vec3::Zero());
  desc.material.youngsModulus = 1e5;
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(std::move(desc), &body), Status::Ok) << lastError();
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.tasks = tasks.get();
  // Squash to half its height, then let go while pushing one corner hard.
  std::vector<double> x(body->positions().begin(), body->positions().end());
  for (size_t i = 1; i < x.size(); i += 3) x[i] *= 0.5;
  ASSERT_EQ(body->setPositions(x.data(), static_cast<int64_t>(x.size())), Status::Ok);
  for (int step = 0; step < 60; ++step) {
    ASSERT_EQ(body->applyForce(0, Vec3(-2e4, 0, 0)), Status::Ok);
    ActorStats stats;
    body->step(in, &stats);
    ASSERT_FALSE(stats.diverged) << "step " << step;
  }
  EXPECT_GT(body->kineticEnergy(), 1.0);
}


// A contact the first solve finds pulling (here: a body stretched upright, its bottom nodes
// about to land) is released and the system solved again, also when the frame's share ran out
// before that re-solve: only the accuracy floor's deadline may skip it. Skipped, the released
// nodes kept the collider's velocity, and under a busy frame budget a body touching a moving
// collider stayed glued to it, the constraints pumping energy into it frame after frame.
TEST(DeformableContacts, AReleasedContactIsSolvedAgainWhenOnlyTheFramesShareRanOut) {
  DeformableDesc desc;
  desc.mesh = makeBoxTetMesh({3, 3, 3}, Vec3(0.5, 0.5, 0.5), Vec3::Zero());
  desc.material.youngsModulus = 1e5;
  desc.material.friction = 0.0;
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(std::move(desc), &body), Status::Ok) << lastError();
  std::vector<double> x(body->positions().begin(), body->positions().end());
  for (size_t i = 1; i < x.size(); i += 3) x[i] = 1.3 * x[i] + 1e-4;  // stretched, just above y = 0
  ASSERT_EQ(body->setPositions(x.data(), static_cast<int64_t>(x.size())), Status::Ok);
  std::vector<double> v(x.size(), 0.0);
  for (size_t i = 1; i < v.size(); i += 3) v[i] = -0.05;
  ASSERT_EQ(body->setVelocities(v.data(), static_cast<int64_t>(v.size())), Status::Ok);
  ColliderShape ground;
  ground.kind = ShapeKind::Plane;
  PreparedCollider prepared;
  ASSERT_EQ(prepareCollider(ground, &prepared), Status::Ok);
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  testutil::TickClock clock;
  DeformableStepInput in;
  in.tasks = tasks.get();
  in.colliders.push_back(ContactCollider{&prepared, 0.0, 1, 1});
  in.deadline = Deadline(clock.clock(), 1e-9);  // the share is spent before the step starts
  ActorStats stats;
  body->step(in, &stats);
  ASSERT_FALSE(stats.diverged);
  // The stretched body contracts: its bottom nodes rise instead of landing.
  double bottomVelocity = 0.0;
  int bottom = 0;
  for (int32_t i = 0; i < body->nodeCount(); ++i)
    if (x[3 * i + 1] < 1e-3) bottomVelocity += body->velocities()[3 * i + 1], ++bottom;
  ASSERT_GT(bottom, 0);
  EXPECT_GT(bottomVelocity / bottom, 0.0);
}

}  // namespace
}  // namespace vp
