// The viscous traction on rigid bodies (fluid/solids/viscous_traction.h): the exchange with the
// fluid's viscous step is equal and opposite, linear and angular momentum both, and a ball the
// pressure cannot turn spins down in a viscous liquid.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include <Eigen/Eigenvalues>

#include "fluid/solids/face_fraction_field.h"
#include "fluid/solids/viscous_traction.h"
#include "fluid/viscosity.h"
#include "fluid_liquid_test_util.h"
#include "liquid_tank_world.h"
#include "spin_down_check.h"
#include "viscous_exchange_step.h"
#include "world.h"

namespace vp {
namespace {

// A sphere translating and spinning through still fluid, its walls 14 cells away (the implicit
// step's spread there is below round-off). Over one step the fluid's momentum grows by minus
// the impulse the ball takes. Its angular momentum about the ball's centre does so only up to what the viscous step moves
// between faces: the Laplacian form of the viscous force conserves angular momentum only for a
// divergence-free flow, which one step without a projection is not (a few thousandths of it
// here; docs/choices.md has the figure).
TEST(FluidViscousTraction, ARigidBodyTakesMinusWhatTheFluidsViscousStepTookLinearAndAngular) {
  const Vec3 centre(0.5, 0.5, 0.5), velocity(0.3, -0.2, 0.1), spin(1.0, 2.0, -1.5);
  ColliderShape shape;
  shape.kind = ShapeKind::Sphere;
  shape.radius = 0.2;
  shape.translation = centre;
  shape.linearVelocity = velocity;
  shape.angularVelocity = spin;
  PreparedCollider ball;
  ASSERT_EQ(prepareCollider(shape, &ball), Status::Ok) << lastError();
  MacGridSpec spec;
  spec.h = 1.0 / 48;
  spec.nx = spec.ny = spec.nz = 48;
  FaceFractionField field;
  ASSERT_EQ(initFaceFractionField(spec, &field), Status::Ok);
  const PreparedCollider* solids = &ball;
  ASSERT_EQ(computeFaceFractions(&solids, 1, &field), Status::Ok);
  const double nu = 1e-3, dt = 1.0 / 60.0, density = 1000.0, h = spec.h;
  MacGrid grid;
  ViscosityWorkspace work;
  ASSERT_NO_FATAL_FAILURE(testutil::viscousStepFromRest(field, nu, dt, &grid, &work));
  // The fluid's faces only: a covered face's velocity is the solid's, not fluid momentum.
  Vec3 momentum = Vec3::Zero(), angular = Vec3::Zero();
  testutil::forEachFace(grid, [&](int a, int i, int j, int k, size_t f) {
    if (work.unknownOfFace[a][f] < 0) return;
    const Vec3 p = density * h * h * h * grid.velocity[a][f] * Vec3::Unit(a);
    momentum += p;
    angular += (grid.faceCentre(a, i, j, k) - centre).cross(p);
  });
  RigidDrag drag;
  addViscousTractionOnCollider(grid, work, density, dt, ball, &drag);
  // The drag at the motion the step saw.
  PressureLoad load;
  load.force = drag.forceAtRest - drag.linear.cwiseProduct(velocity);
  load.torque = drag.torqueAtRest - drag.angular * spin;
  EXPECT_TRUE((drag.linear.array() > 0.0).all());
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat3>(drag.angular).eigenvalues().minCoeff(), 0.0);
  std::printf("fluid momentum %.6g %.6g %.6g, angular %.6g %.6g %.6g; ball impulse %.6g %.6g %.6g, angular "
              "%.6g %.6g %.6g\n",
              momentum.x(), momentum.y(), momentum.z(), angular.x(), angular.y(), angular.z(), load.force.x() * dt,
              load.force.y() * dt, load.force.z() * dt, load.torque.x() * dt, load.torque.y() * dt,
              load.torque.z() * dt);
  ASSERT_GT(momentum.norm(), 0.0);
  ASSERT_GT(angular.norm(), 0.0);
  EXPECT_LT((momentum + load.force * dt).norm(), 1e-9 * momentum.norm());
  EXPECT_LT((angular + load.torque * dt).norm(), 1e-2 * angular.norm());
  // It drags the ball back and spins it down.
  EXPECT_LT(load.force.dot(velocity), 0.0);
  EXPECT_LT(load.torque.dot(spin), 0.0);
}

// A dynamic ball of `density` in the test tank's liquid, spinning about the vertical and moving
// along x, without Bullet's damping.
ColliderDesc ballInTheTank(double density, double radius, double spin, double speed) {
  ColliderDesc d;
  d.bodyType = BodyType::Dynamic;
  d.shape.type = ShapeType::Sphere;
  d.shape.radius = radius;
  d.mass = density * 4.0 / 3.0 * M_PI * radius * radius * radius;
  d.angularDamping = 0.0;
  d.pose.position = Vec3(0.5, 0.4, 0.5);
  d.angularVelocity = Vec3(0.0, spin, 0.0);
  d.linearVelocity = Vec3(speed, 0.0, 0.0);
  return d;
}

// A rigid ball of the liquid's density spinning about the vertical in a still liquid, in zero
// gravity and without Bullet's damping: the fraction of its spin left after `seconds`.
double rigidSpinLeft(double kinematicViscosity, double seconds) {
  const double radius = 0.2, spin = 3.0;
  FluidHandle fluid;
  std::unique_ptr<World> world = testutil::worldWithOpenTank(24, 0.85, 1e-8, &fluid, kinematicViscosity);
  if (!world) return 0.0;
  EXPECT_EQ(world->setGravity(Vec3::Zero()), Status::Ok);
  ColliderHandle ball;
  EXPECT_EQ(world->createCollider(ballInTheTank(1000.0, radius, spin, 0.0), &ball), Status::Ok) << lastError();
  for (int s = 0; s < static_cast<int>(std::lround(seconds * 60.0)); ++s)
    EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok);
  return world->collider(ball)->angularVelocity().y() / spin;
}

// The same figure as the deformable ball's (deform_in_fluid_test.cpp,
// ViscousTractionSpinsDownABallThatPressureCannotTurn), with the same bounds and for the same
// reasons: the leading-order loss of an impulsively started ball, w / w0 = exp(-10 (rho /
// rho_ball) sqrt(nu t / pi) / R), which the unresolved layer on this 24^3 grid lowers.
TEST(FluidViscousTraction, ARigidBallThePressureCannotTurnSpinsDownInAViscousLiquid) {
  const double seconds = 0.5, nu = 0.01, radius = 0.2;
  const double inviscid = rigidSpinLeft(0.0, seconds), viscous = rigidSpinLeft(nu, seconds);
  const double predicted = std::exp(-10.0 * std::sqrt(nu * seconds / M_PI) / radius);
  std::printf("rigid ball, spin left after %.1f s: inviscid %.5f, nu = %g %.4f (leading order %.4f)\n", seconds,
              inviscid, nu, viscous, predicted);
  EXPECT_NEAR(inviscid, 1.0, 1e-3);
  EXPECT_GE(1.0 - viscous, 0.5 * (1.0 - predicted));
  EXPECT_LE(1.0 - viscous, 1.0 - predicted);
}

// A light ball (density 200, R = 0.1 m) spinning at 3 rad/s and moving at 0.5 m/s in a liquid
// of nu = 0.05, zero gravity: the drag its faces couple is more than its mass can take
// explicitly over a step, and without the implicit response the spin reached 1e4 rad/s in six
// frames. With it the spin and the speed fall every frame, never past zero, to a tenth.
TEST(FluidViscousTraction, ALightBallInAThickLiquidSpinsAndSlowsDownWithoutOvershooting) {
  const double radius = 0.1, spin = 3.0, speed = 0.5;
  FluidHandle fluid;
  std::unique_ptr<World> world = testutil::worldWithOpenTank(24, 0.85, 1e-8, &fluid, 0.05);
  ASSERT_TRUE(world);
  ASSERT_EQ(world->setGravity(Vec3::Zero()), Status::Ok);
  ColliderHandle ball;
  ASSERT_EQ(world->createCollider(ballInTheTank(200.0, radius, spin, speed), &ball), Status::Ok) << lastError();
  const Collider& body = *world->collider(ball);
  const testutil::SpinAndSpeed last = testutil::stepWhileSpinAndSpeedFall(*world, 60, [&] {
    return testutil::SpinAndSpeed{body.angularVelocity().y(), body.linearVelocity().x()};
  });
  ASSERT_GE(last.spin, 0.0);
  std::printf("light ball in nu = 0.05 after 1 s: spin %.4f of its start, speed %.4f\n", last.spin / spin,
              last.speed / speed);
  EXPECT_LT(last.spin, 0.1 * spin);
  EXPECT_LT(last.speed, 0.1 * speed);
}

// A ball of R = 0.1 m pushed by a steady host force of 5 N through a still liquid of nu = 0.05
// (Reynolds number below 1), zero gravity: its speed along the push, the mean over frames 60-89.
double terminalSpeed(double density) {
  const double radius = 0.1, force = 5.0;
  FluidHandle fluid;
  std::unique_ptr<World> world = testutil::worldWithOpenTank(24, 0.85, 1e-8, &fluid, 0.05);
  if (!world) return 0.0;
  EXPECT_EQ(world->setGravity(Vec3::Zero()), Status::Ok);
  ColliderDesc d = ballInTheTank(density, radius, 0.0, 0.0);
  d.linearDamping = 0.0;
  d.pose.position.x() = 0.35;
  ColliderHandle ball;
  EXPECT_EQ(world->createCollider(d, &ball), Status::Ok) << lastError();
  double sum = 0.0;
  for (int s = 0; s < 90; ++s) {
    world->collider(ball)->addHostLoad(Vec3(force, 0.0, 0.0), Vec3::Zero());
    EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok);
    if (s >= 60) sum += world->collider(ball)->linearVelocity().x() / 30.0;
  }
  return sum;
}

// At its terminal speed the drag balances the push, whatever the ball's mass: a light ball and
// a heavy one move alike. Stokes' drag 6 pi mu R v of an unbounded liquid is a lower bound on
// the drag here (the tank's walls and the no-slip condition a cell out add to it), so the speed
// is at most F / (6 pi mu R), and no less than half of it (walls 2.5 radii away). While the
// stabilizations scaled the traction down by 1 + (m_a + D T) / m, the light ball outran
// Stokes' speed many times over (docs/choices.md).
TEST(FluidViscousTraction, APushedBallsTerminalSpeedIsStokesAndDoesNotDependOnItsMass) {
  const double mu = 1000.0 * 0.05, stokes = 5.0 / (6.0 * M_PI * mu * 0.1);
  const double light = terminalSpeed(200.0), heavy = terminalSpeed(2000.0);
  std::printf("terminal speed of a ball pushed with 5 N: density 200 %.5f, 2000 %.5f m/s (Stokes %.5f)\n", light,
              heavy, stokes);
  EXPECT_NEAR(light, heavy, 0.05 * heavy);
  for (double v : {light, heavy}) {
    EXPECT_LE(v, stokes);
    EXPECT_GE(v, 0.5 * stokes);
  }
}

}  // namespace
}  // namespace vp
