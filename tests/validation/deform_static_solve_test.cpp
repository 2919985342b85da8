// The static solve (deform/static_equilibrium.h) against the converged stepping reference and
// beam theory, a patch test, a jelly resting on a plane, a thin plate, and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "deform/static_equilibrium.h"
#include "static_beam.h"
#include "world.h"

namespace vp {
namespace {

std::vector<int32_t> nodesAtX(const DeformableBody& body, double x) {
  std::vector<int32_t> out;
  for (int32_t i = 0; i < body.nodeCount(); ++i)
    if (std::abs(body.restPositions()[3 * i] - x) < 1e-9) out.push_back(i);
  return out;
}

double meanDrop(const DeformableBody& body, const std::vector<int32_t>& nodes) {
  double sum = 0.0;
  for (int32_t i : nodes) sum += body.restPositions()[3 * i + 1] - body.positions()[3 * i + 1];
  return sum / static_cast<double>(nodes.size());
}

struct Solved {
  Status status;
  StaticSolveResult result;
  double tip;
};

// The beam clamped at x = 0, solved statically under gravity (and tipForce on each free-end node).
Solved solveBeam(const Beam& beam, int degree, TetMesh mesh, double tolerance, int maxIterations = 100,
                 double tipForce = 0.0) {
  std::unique_ptr<DeformableBody> body;
  EXPECT_EQ(DeformableBody::create(beamDeformableDesc(beam, degree, std::move(mesh)), &body), Status::Ok) << lastError();
  const std::vector<int32_t> clamped = nodesAtX(*body, 0.0), tip = nodesAtX(*body, beam.length);
  body->setPinned(clamped.data(), static_cast<int64_t>(clamped.size()), true);
  for (int32_t i : tip)
    if (tipForce != 0.0) body->applyForce(i, Vec3(0, -tipForce / static_cast<double>(tip.size()), 0));
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.tasks = tasks.get();
  in.gravity = Vec3(0, -beam.g, 0);
  Solved s;
  s.status = solveStaticEquilibrium(*body, in, maxIterations, tolerance, &s.result);
  s.tip = meanDrop(*body, tip);
  return s;
}

TEST(StaticSolve, CantileverMatchesTheConvergedSteppingReferenceForEachDegree) {
  const Beam beam;
  for (int degree : {1, 2, 3}) {
    const double reference = staticTipDeflection(beam, degree, beamTetMesh(beam, 8, 2), nullptr);
    const Solved s = solveBeam(beam, degree, beamTetMesh(beam, 8, 2), 1e-8);
    ASSERT_EQ(s.status, Status::Ok) << "degree " << degree << ": " << lastError();
    EXPECT_TRUE(s.result.converged);
    EXPECT_LE(s.result.residual, 1e-8);
    // Same mesh and degree: the two differ only by what each solve left unconverged.
    EXPECT_NEAR(s.tip, reference, 1e-5 * reference) << "degree " << degree;
    // And the higher degrees are where the validation suite puts them against beam theory.
    if (degree > 1) {
      EXPECT_NEAR(s.tip, beam.analyticTipDeflection(), 0.03 * beam.analyticTipDeflection());
    }
  }
}

// A plate one hundredth as thick as it is long, clamped at one end, a load at the other:
// Euler–Bernoulli's P L³ / (3 E I) (shear is negligible at this slenderness).
TEST(StaticSolve, ThinPlateUnderATipLoadConverges) {
  Beam plate;
  plate.length = 1.0, plate.height = 0.01, plate.width = 0.2;
  plate.E = 2e9, plate.rho = 1000.0, plate.g = 0.0;
  const double P = 0.1;
  const double I = plate.width * plate.height * plate.height * plate.height / 12.0;
  const double theory = P * plate.length * plate.length * plate.length / (3.0 * plate.E * I);
  double tip[4] = {};
  for (int degree : {1, 2, 3}) {
    // The plate's internal forces are large beside the load (stiff and thin), and their
    // rounding puts a floor of a few 1e-6 under the relative residual: ask for 1e-4.
    // Cubes 5 x 1 x 5 thicknesses in size, one through the thickness.
    const TetMesh mesh = makeBoxTetMesh({20, 1, 4}, Vec3(plate.length, plate.height, plate.width),
                                        Vec3(0, -0.5 * plate.height, -0.5 * plate.width));
    const Solved s = solveBeam(plate, degree, mesh, 1e-4, 100, P);
    ASSERT_EQ(s.status, Status::Ok) << "degree " << degree << ": " << lastError();
    EXPECT_LT(s.result.iterations, 20) << "degree " << degree;
    tip[degree] = s.tip;
    // One layer of linear tets locks in bending, so only the higher degrees meet the theory.
    if (degree > 1) {
      EXPECT_NEAR(s.tip, theory, 0.05 * theory) << "degree " << degree;
    }
  }
  // Minimum potential energy: on one mesh the linear space lies inside the cubic one, so the
  // linear plate is stiffer (its tip deflects less), and both deflect downwards.
  EXPECT_GT(tip[1], 0.0);
  EXPECT_LT(tip[1], tip[3]);
}

// Boundary nodes placed by an affine map and held: the interior settles at the same map.
TEST(StaticSolve, PatchTestInteriorFollowsTheBoundarysAffineMap) {
  for (int degree : {1, 2, 3}) {
    DeformableDesc desc;
    desc.degree = degree;
    desc.mesh = makeBoxTetMesh({3, 3, 3}, Vec3(1, 1, 1), Vec3(0, 0, 0));
    desc.solver.tolerance = 1e-10;
    desc.solver.maxIterations = 5000;
    std::unique_ptr<DeformableBody> body;
    ASSERT_EQ(DeformableBody::create(desc, &body), Status::Ok) << lastError();
    Eigen::Matrix3d F;
    F << 1.05, 0.02, 0.0, -0.01, 0.97, 0.03, 0.0, 0.01, 1.02;
    const Array<double>& rest = body->restPositions();
    auto mapped = [&](int32_t i) { return Vec3(F * Vec3(rest[3 * i], rest[3 * i + 1], rest[3 * i + 2])); };
    std::vector<int32_t> boundary;
    for (int32_t i = 0; i < body->nodeCount(); ++i) {
      const Vec3 X(rest[3 * i], rest[3 * i + 1], rest[3 * i + 2]);
      if ((X.array() < 1e-9).any() || (X.array() > 1 - 1e-9).any()) boundary.push_back(i);
    }
    // Pinning the boundary also pins control points of interior edges between boundary
    // vertices: every held node goes on the map, every free one starts off it.
    body->setPinned(boundary.data(), static_cast<int64_t>(boundary.size()), true);
    Array<double> x(rest.size());
    int32_t free = 0;
    for (int32_t i = 0; i < body->nodeCount(); ++i) {
      const Vec3 y = mapped(i) + (body->pinned(i) ? Vec3::Zero() : Vec3(0.03, -0.02, 0.01));
      free += body->pinned(i) ? 0 : 1;
      for (int k = 0; k < 3; ++k) x[3 * i + k] = y[k];
    }
    ASSERT_GT(free, 0) << "degree " << degree;
    ASSERT_EQ(body->setPositions(x.data(), static_cast<int64_t>(x.size())), Status::Ok);
    auto tasks = TaskSystem::create(TaskHooks{}, 1);
    DeformableStepInput in;
    in.tasks = tasks.get();
    StaticSolveResult result;
    ASSERT_EQ(solveStaticEquilibrium(*body, in, 100, 1e-9, &result), Status::Ok) << lastError();
    double worst = 0.0;
    for (int32_t i = 0; i < body->nodeCount(); ++i) {
      const Vec3 y(body->positions()[3 * i], body->positions()[3 * i + 1], body->positions()[3 * i + 2]);
      worst = std::max(worst, (y - mapped(i)).norm());
    }
    EXPECT_LT(worst, 1e-7) << "degree " << degree << " after " << result.iterations << " iterations";
  }
}

struct JellyOnPlane {
  std::unique_ptr<World> world;
  DeformableHandle jelly;
};

// A 0.4 m jelly whose bottom starts `gap` above a ground plane at y = 0.
JellyOnPlane jellyOnPlane(double gap) {
  JellyOnPlane s;
  WorldConfig config;
  config.gravity = Vec3(0, -9.81, 0);
  config.frameBudgetMs = 0.0;
  EXPECT_EQ(World::create(config, &s.world), Status::Ok) << lastError();
  ColliderDesc ground;
  ground.shape.type = ShapeType::Plane;
  ColliderHandle groundHandle;
  EXPECT_EQ(s.world->createCollider(ground, &groundHandle), Status::Ok) << lastError();
  DeformableDesc desc;
  desc.degree = 2;
  desc.mesh = makeBoxTetMesh({3, 3, 3}, Vec3(0.4, 0.4, 0.4), Vec3(-0.2, gap, -0.2));
  desc.material.youngsModulus = 2e5;
  desc.material.poissonRatio = 0.4;
  desc.material.density = 1100;
  EXPECT_EQ(s.world->createDeformable(desc, &s.jelly), Status::Ok) << lastError();
  return s;
}

TEST(StaticSolve, AJellyRestsOnAPlaneWithoutPenetration) {
  for (double gap : {0.0, 0.05}) {
    JellyOnPlane s = jellyOnPlane(gap);
    StaticSolveResult result;
    ASSERT_EQ(s.world->solveDeformableStatic(s.jelly, 200, 1e-4, &result), Status::Ok)
        << "gap " << gap << ": " << lastError();
    const DeformableBody& body = *s.world->deformable(s.jelly);
    double lowest = 1e9, sag = 0.0;
    for (int32_t i = 0; i < body.nodeCount(); ++i) {
      lowest = std::min(lowest, body.positions()[3 * i + 1]);
      sag = std::max(sag, std::abs(body.velocities()[3 * i]) + std::abs(body.velocities()[3 * i + 1]) +
                              std::abs(body.velocities()[3 * i + 2]));
    }
    EXPECT_EQ(sag, 0.0) << "at rest";
    EXPECT_GE(lowest, -1e-6) << "gap " << gap;
    EXPECT_LT(lowest, 0.01) << "gap " << gap << ": it must reach the ground";
    // Resting on the ground it squashes a little under its weight: the top sits lower than 0.4.
    double top = -1e9;
    for (int32_t i = 0; i < body.nodeCount(); ++i) top = std::max(top, body.positions()[3 * i + 1]);
    EXPECT_LT(top, lowest + 0.4 - 1e-4) << "gap " << gap;
    // And it stays there: a step from the equilibrium barely moves it.
    ASSERT_EQ(s.world->step(1.0 / 60.0), Status::Ok) << lastError();
    double speed = 0.0;
    for (double v : body.velocities()) speed = std::max(speed, std::abs(v));
    EXPECT_LT(speed, 1e-2) << "gap " << gap;
  }
}

TEST(StaticSolve, BadArgumentsAreNamedAndChangeNothing) {
  JellyOnPlane s = jellyOnPlane(0.05);
  const DeformableBody& body = *s.world->deformable(s.jelly);
  const Array<double> x0 = body.positions();
  StaticSolveResult result;
  EXPECT_EQ(s.world->solveDeformableStatic(s.jelly, 0, 1e-4, &result), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("maxIterations = 0"), std::string::npos) << lastError();
  for (double bad : {0.0, 1.0, -1.0, std::nan("")}) {
    EXPECT_EQ(s.world->solveDeformableStatic(s.jelly, 10, bad, &result), Status::InvalidArgument) << bad;
    EXPECT_NE(std::string(lastError()).find("tolerance = "), std::string::npos) << lastError();
  }
  EXPECT_EQ(s.world->solveDeformableStatic(DeformableHandle{}, 10, 1e-4, &result), Status::InvalidId);
  // One iteration cannot reach 1e-10 from 5 cm up: NotConverged, and the jelly is where it was.
  EXPECT_EQ(s.world->solveDeformableStatic(s.jelly, 1, 1e-10, &result), Status::NotConverged);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_FALSE(result.converged);
  EXPECT_NE(std::string(lastError()).find("unchanged"), std::string::npos) << lastError();
  EXPECT_EQ(body.positions(), x0);
}

}  // namespace
}  // namespace vp
