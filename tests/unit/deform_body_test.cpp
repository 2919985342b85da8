// The linear deformable actor: elasticity invariants, constraints, integration, bad input.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "deform/deformable_body.h"
#include "deform_test_util.h"
#include "geometry/box_tet_mesh.h"
#include "random_values.h"

namespace vp {
namespace {

const Vec3 kLo(-0.2, 0.1, 0.3), kSize(1.5, 1.2, 0.9);

// A 3x3x3-cube box whose interior vertices are jittered: an irregular mesh for patch tests.
TetMesh irregularBox() {
  TetMesh mesh = makeBoxTetMesh({3, 3, 3}, kSize, kLo);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.06, 0.06);
  for (int k = 1; k < 3; ++k)
    for (int j = 1; j < 3; ++j)
      for (int i = 1; i < 3; ++i) mesh.vertices[i + 4 * (j + 4 * k)] += testing_values::randomVector(jitter, rng);
  return mesh;
}

bool onBoundary(const Vec3& X) {
  const Vec3 hi = kLo + kSize;
  for (int k = 0; k < 3; ++k)
    if (std::abs(X[k] - kLo[k]) < 1e-12 || std::abs(X[k] - hi[k]) < 1e-12) return true;
  return false;
}

std::unique_ptr<DeformableBody> makeBody(TetMesh mesh, double E = 1e6, double nu = 0.3) {
  DeformableDesc desc;
  desc.mesh = std::move(mesh);
  desc.material.youngsModulus = E;
  desc.material.poissonRatio = nu;
  std::unique_ptr<DeformableBody> body;
  EXPECT_EQ(DeformableBody::create(std::move(desc), &body), Status::Ok) << lastError();
  return body;
}

// Places every node at x = A X + t.
void deformAffine(DeformableBody& body, const Mat3& A, const Vec3& t) {
  const Array<double>& X = body.restPositions();
  std::vector<double> x(X.size());
  for (size_t i = 0; i < X.size() / 3; ++i) {
    const Vec3 p = A * Vec3(X[3 * i], X[3 * i + 1], X[3 * i + 2]) + t;
    for (int k = 0; k < 3; ++k) x[3 * i + k] = p[k];
  }
  ASSERT_EQ(body.setPositions(x.data(), static_cast<int64_t>(x.size())), Status::Ok);
}

double maxNodeForce(const Array<double>& f) {
  double m = 0.0;
  for (size_t i = 0; i < f.size() / 3; ++i) m = std::max(m, Vec3(f[3 * i], f[3 * i + 1], f[3 * i + 2]).norm());
  return m;
}

Mat3 randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return testing_values::randomQuaternion(g, rng).toRotationMatrix();
}

// Patch test: under any affine deformation every interior node is in equilibrium (the
// element forces cancel), on an irregular mesh, including a large rotation of the strain.
TEST(DeformableBody, PatchTestInteriorForcesVanishUnderAffineDeformation) {
  auto body = makeBody(irregularBox());
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    Mat3 strain = Mat3::Identity();
    std::uniform_real_distribution<double> u(-0.02, 0.02);
    for (int i = 0; i < 9; ++i) strain(i / 3, i % 3) += u(rng);
    const Mat3 A = randomRotation(rng) * strain;
    deformAffine(*body, A, Vec3(0.3, -1.0, 2.0));
    Array<double> f;
    body->elasticForces(*tasks, &f);
    const Array<double>& X = body->restPositions();
    double interiorMax = 0.0;
    int interior = 0;
    for (int32_t i = 0; i < body->nodeCount(); ++i) {
      if (onBoundary(Vec3(X[3 * i], X[3 * i + 1], X[3 * i + 2]))) continue;
      ++interior;
      interiorMax = std::max(interiorMax, Vec3(f[3 * i], f[3 * i + 1], f[3 * i + 2]).norm());
    }
    ASSERT_EQ(interior, 8);
    // Boundary forces are O(E ε h²) ~ 1e6 * 0.02 * 0.1 = 2e3 N; round-off is ~1e-16 of that
    // times the number of contributions; 1e-9 relative leaves ample margin and still fails
    // for any real inconsistency (an O(1) error in one gradient gives ~1e-1 relative).
    EXPECT_LT(interiorMax, 1e-9 * maxNodeForce(f)) << "trial " << trial;
    EXPECT_GT(maxNodeForce(f), 10.0);
  }
}

TEST(DeformableBody, NoElasticForceUnderLargeRigidMotion) {
  auto body = makeBody(irregularBox());
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    deformAffine(*body, randomRotation(rng), Vec3(5.0 * trial, -3.0, 1.0));
    Array<double> f;
    body->elasticForces(*tasks, &f);
    // Compare with the force of a 1% stretch: E * 0.01 * (face area ~ 0.1 m²) ~ 1e3 N.
    EXPECT_LT(maxNodeForce(f), 1e-6) << "trial " << trial;
    EXPECT_LT(body->elasticEnergy(*tasks), 1e-12);
  }
}

TEST(DeformableBody, StepMatrixIsSymmetricPositiveDefinite) {
  auto body = makeBody(irregularBox());
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  std::mt19937 rng(9);
  Mat3 A = randomRotation(rng) * (Mat3::Identity() + 0.05 * Mat3::Random());
  deformAffine(*body, A, Vec3::Zero());
  DeformableStepInput in;
  in.tasks = tasks.get();
  ActorStats stats;
  body->step(in, &stats);
  const BlockSparseMatrix<double>& m = body->stepMatrix();
  const int n = m.blockRows;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (int r = 0; r < n; ++r)
    for (int k = m.rowStart[r]; k < m.rowStart[r + 1]; ++k)
      for (int i = 0; i < 9; ++i) dense(3 * r + i / 3, 3 * m.columns[k] + i % 3) = m.values[9 * k + i];
  EXPECT_LT((dense - dense.transpose()).norm(), 1e-12 * dense.norm());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (dense + dense.transpose()));
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
}

// A stretched, unconstrained body in zero gravity: with damping its total energy (kinetic +
// elastic) may only fall, step after step, and it ends near rest.
TEST(DeformableBody, EnergyDecaysWithDamping) {
  auto body = makeBody(makeBoxTetMesh({4, 2, 2}, Vec3(2, 1, 1), Vec3::Zero()), 1e5, 0.3);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  Mat3 stretch = Mat3::Identity();
  stretch(0, 0) = 1.2;
  deformAffine(*body, stretch, Vec3::Zero());
  DeformableStepInput in;
  in.tasks = tasks.get();
  double previous = body->elasticEnergy(*tasks);
  const double initial = previous;
  for (int i = 0; i < 120; ++i) {
    ActorStats stats;
    body->step(in, &stats);
    ASSERT_FALSE(stats.diverged);
    const double energy = body->kineticEnergy() + body->elasticEnergy(*tasks);
    // Backward Euler's numerical damping and the Rayleigh term both dissipate; allow the
    // solver tolerance's worth of noise (1e-3 relative residual) per step.
    EXPECT_LT(energy, previous * (1.0 + 1e-3)) << "step " << i;
    previous = energy;
  }
  EXPECT_LT(previous, 0.05 * initial);
}

// Momentum: no gravity, no constraints, an initial velocity: the centre of mass moves with
// exactly that velocity (internal forces sum to zero).
TEST(DeformableBody, FreeBodyKeepsItsMomentum) {
  DeformableDesc desc;
  desc.mesh = irregularBox();
  desc.linearVelocity = Vec3(1.0, -2.0, 0.5);
  desc.solver.tolerance = 1e-10;
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(desc, &body), Status::Ok);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.tasks = tasks.get();
  for (int i = 0; i < 30; ++i) {
    ActorStats stats;
    body->step(in, &stats);
  }
  Vec3 momentum = Vec3::Zero();
  double mass = 0.0;
  for (int32_t i = 0; i < body->nodeCount(); ++i) {
    const double m = body->nodeMasses()[i];
    momentum += m * Vec3(body->velocities()[3 * i], body->velocities()[3 * i + 1], body->velocities()[3 * i + 2]);
    mass += m;
  }
  EXPECT_NEAR(mass, 1000.0 * 1.5 * 1.2 * 0.9, 1e-9);
  EXPECT_LT((momentum / mass - desc.linearVelocity).norm(), 1e-8);
}

// Permuting the corners of every tet (odd permutations get repaired by the validator)
// gives the same motion to solver precision.
TEST(DeformableBody, InvariantToTetVertexOrdering) {
  auto run = [](bool permute) {
    DeformableDesc desc;
    desc.mesh = makeBoxTetMesh({6, 2, 2}, Vec3(3, 1, 1), Vec3::Zero());
    if (permute)
      for (size_t t = 0; t < desc.mesh.tets.size(); ++t) {
        auto& tet = desc.mesh.tets[t];
        if (t % 3 == 0) tet = {tet[1], tet[2], tet[3], tet[0]};  // odd: inverted, repaired
        if (t % 3 == 1) tet = {tet[2], tet[3], tet[0], tet[1]};  // even
      }
    desc.material.youngsModulus = 1e6;
    desc.solver.tolerance = 1e-10;
    desc.solver.maxIterations = 2000;
    std::unique_ptr<DeformableBody> body;
    EXPECT_EQ(DeformableBody::create(desc, &body), Status::Ok) << lastError();
    deform_test::pinNodesAtX(*body, 0.0);
    auto tasks = TaskSystem::create(TaskHooks{}, 1);
    DeformableStepInput in;
    in.tasks = tasks.get();
    in.gravity = Vec3(0, -9.81, 0);
    for (int i = 0; i < 20; ++i) {
      ActorStats stats;
      body->step(in, &stats);
    }
    return std::vector<double>(body->positions().begin(), body->positions().end());
  };
  const std::vector<double> a = run(false), b = run(true);
  ASSERT_EQ(a.size(), b.size());
  double maxDiff = 0.0, tipDrop = 0.0;
  for (size_t i = 0; i < a.size(); ++i) maxDiff = std::max(maxDiff, std::abs(a[i] - b[i]));
  for (size_t i = 1; i < a.size(); i += 3) tipDrop = std::max(tipDrop, -a[i]);
  EXPECT_GT(tipDrop, 1e-3);                // the beam really bent...
  EXPECT_LT(maxDiff, 1e-7 * (1 + tipDrop));  // ...identically, up to the 1e-10 solver tolerance
}

// The render mesh is evaluated from the tets: under a rigid motion of the nodes it moves
// rigidly too, to round-off (here an explicit render mesh strictly inside the tets).
TEST(DeformableBody, RenderMeshFollowsARigidMotionExactly) {
  DeformableDesc desc;
  desc.mesh = irregularBox();
  SurfaceMesh render;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int i = 0; i < 50; ++i)
    render.vertices.push_back(kLo + kSize.cwiseProduct(testing_values::randomVector(u, rng)));
  for (int i = 0; i + 2 < 50; i += 3) render.triangles.push_back({i, i + 1, i + 2});
  desc.renderMesh = render;
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(desc, &body), Status::Ok) << lastError();
  const Mat3 R = randomRotation(rng);
  const Vec3 t(1.0, -2.0, 0.5);
  deformAffine(*body, R, t);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;  // no gravity: a rigidly placed body stays put
  in.tasks = tasks.get();
  ActorStats stats;
  body->step(in, &stats);
  ASSERT_EQ(body->renderPositions().size(), render.vertices.size());
  for (size_t i = 0; i < render.vertices.size(); ++i)
    EXPECT_LT((body->renderPositions()[i] - (R * render.vertices[i] + t)).norm(), 1e-9) << i;
}

// An element pushed through itself (inverted) is pushed back out: the rotation stays proper
// and the corotated force restores the rest shape.
TEST(DeformableBody, InvertedElementRecovers) {
  DeformableDesc desc;
  desc.mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  desc.mesh.tets = {{0, 1, 2, 3}};
  desc.material.youngsModulus = 1e4;
  desc.material.density = 100;
  desc.solver.tolerance = 1e-8;
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(desc, &body), Status::Ok);
  const int32_t base[] = {0, 1, 2};
  body->setPinned(base, 3, true);
  std::vector<double> x(body->positions().begin(), body->positions().end());
  x[3 * 3 + 2] = -0.5;  // apex through the base plane: signed volume negative
  ASSERT_EQ(body->setPositions(x.data(), static_cast<int64_t>(x.size())), Status::Ok);
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  DeformableStepInput in;
  in.tasks = tasks.get();
  for (int i = 0; i < 240; ++i) {
    ActorStats stats;
    body->step(in, &stats);
    ASSERT_FALSE(stats.diverged);
  }
  EXPECT_NEAR(body->positions()[3 * 3 + 2], 1.0, 0.05);  // back at the rest apex
}

TEST(DeformableBody, PinnedNodesStayAndOthersFall) {
  auto body = makeBody(makeBoxTetMesh({2, 2, 2}, Vec3(1, 1, 1), Vec3::Zero()));
  const int32_t pinned[] = {0, 1};
  ASSERT_EQ(body->setPinned(pinned, 2, true), Status::Ok);
  const Vec3 x0(body->positions()[0], body->positions()[1], body->positions()[2]);
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  DeformableStepInput in;
  in.tasks = tasks.get();
  in.gravity = Vec3(0, -9.81, 0);
  for (int i = 0; i < 30; ++i) {
    ActorStats stats;
    body->step(in, &stats);
  }
  EXPECT_EQ(Vec3(body->positions()[0], body->positions()[1], body->positions()[2]), x0);
  const int32_t far = body->nodeCount() - 1;
  EXPECT_LT(body->positions()[3 * far + 1], 1.0 - 0.05);
}

TEST(DeformableBody, RejectsBadInputAndChangesNothing) {
  auto body = makeBody(makeBoxTetMesh({1, 1, 1}, Vec3(1, 1, 1), Vec3::Zero()));
  const int32_t bad[] = {0, 99};
  EXPECT_EQ(body->setPinned(bad, 2, true), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("nodes[1] = 99"), std::string::npos) << lastError();
  EXPECT_FALSE(body->pinned(0));  // the valid first entry was not applied either
  EXPECT_EQ(body->applyForce(-1, Vec3::Zero()), Status::InvalidArgument);
  EXPECT_EQ(body->applyImpulse(0, Vec3(NAN, 0, 0)), Status::InvalidArgument);
  std::vector<double> v(3 * body->nodeCount(), 0.0);
  v[4] = INFINITY;
  EXPECT_EQ(body->setVelocities(v.data(), static_cast<int64_t>(v.size())), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("velocities[4] = inf"), std::string::npos);
  EXPECT_EQ(body->setVelocities(v.data(), 5), Status::InvalidArgument);
  for (double x : body->velocities()) EXPECT_EQ(x, 0.0);
}

TEST(DeformableBody, DescValidationNamesTheField) {
  struct Case {
    const char* field;
    Status status;
    void (*mutate)(DeformableDesc&);
  } cases[] = {
      {"youngsModulus = -5", Status::InvalidArgument, [](DeformableDesc& d) { d.material.youngsModulus = -5; }},
      {"poissonRatio = 0.5", Status::InvalidArgument, [](DeformableDesc& d) { d.material.poissonRatio = 0.5; }},
      {"density = nan", Status::InvalidArgument, [](DeformableDesc& d) { d.material.density = NAN; }},
      {"stiffnessDamping = -1", Status::InvalidArgument, [](DeformableDesc& d) { d.material.stiffnessDamping = -1; }},
      {"solverTolerance = 0", Status::InvalidArgument, [](DeformableDesc& d) { d.solver.tolerance = 0; }},
      {"solverMaxIterations = 0", Status::InvalidArgument, [](DeformableDesc& d) { d.solver.maxIterations = 0; }},
      {"degree = 4", Status::InvalidArgument, [](DeformableDesc& d) { d.degree = 4; }},
      {"mesh", Status::InvalidArgument, [](DeformableDesc& d) { d.mesh.tets[0][2] = 1000; }},
      {"mesh", Status::InvalidArgument, [](DeformableDesc& d) { d.mesh.vertices[3].x() = NAN; }},
      {"mesh", Status::InvalidArgument, [](DeformableDesc& d) { d.mesh.tets.clear(); }},
      {"pose.position", Status::InvalidArgument, [](DeformableDesc& d) { d.pose.position.y() = INFINITY; }},
  };
  for (const Case& c : cases) {
    DeformableDesc desc;
    desc.mesh = makeBoxTetMesh({1, 1, 1}, Vec3(1, 1, 1), Vec3::Zero());
    c.mutate(desc);
    std::unique_ptr<DeformableBody> body;
    EXPECT_EQ(DeformableBody::create(desc, &body), c.status) << c.field << ": " << lastError();
    EXPECT_NE(std::string(lastError()).find(c.field), std::string::npos) << lastError();
    EXPECT_EQ(body, nullptr);
  }
}

}  // namespace
}  // namespace vp
