// Quadratic and cubic Bernstein–Bézier elements in the deformable actor: shared control
// points, patch test, rigid invariance, pinned faces, and the locking behaviour they exist for.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <set>

#include "static_beam.h"

namespace vp {
namespace {

std::unique_ptr<DeformableBody> makeBody(int degree, TetMesh mesh) {
  DeformableDesc desc;
  desc.degree = degree;
  desc.mesh = std::move(mesh);
  desc.material.youngsModulus = 1e6;
  std::unique_ptr<DeformableBody> body;
  EXPECT_EQ(DeformableBody::create(desc, &body), Status::Ok) << lastError();
  return body;
}

// Edge and face control points are shared between neighbouring tets: degree 2 adds one
// node per unique edge, degree 3 two per edge and one per face.
TEST(HigherOrderElements, ControlPointsAreSharedBetweenTets) {
  const TetMesh mesh = makeBoxTetMesh({2, 1, 1}, Vec3(2, 1, 1), Vec3::Zero());
  std::set<std::pair<int32_t, int32_t>> edges;
  std::set<std::array<int32_t, 3>> faces;
  for (const auto& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        edges.insert({std::min(t[a], t[b]), std::max(t[a], t[b])});
        for (int c = b + 1; c < 4; ++c) {
          std::array<int32_t, 3> f{t[a], t[b], t[c]};
          std::sort(f.begin(), f.end());
          faces.insert(f);
        }
      }
  const int32_t V = static_cast<int32_t>(mesh.vertices.size());
  EXPECT_EQ(makeBody(2, mesh)->nodeCount(), V + static_cast<int32_t>(edges.size()));
  EXPECT_EQ(makeBody(3, mesh)->nodeCount(), V + 2 * static_cast<int32_t>(edges.size()) + static_cast<int32_t>(faces.size()));
}

// Irregular mesh (jittered interior vertex), every node at x = A X + t: interior nodes feel no
// force. BB elements reproduce affine fields exactly, so this holds to round-off.
TEST(HigherOrderElements, PatchTestForDegreesTwoAndThree) {
  TetMesh mesh = makeBoxTetMesh({2, 2, 2}, Vec3(1, 1, 1), Vec3::Zero());
  mesh.vertices[1 + 3 * (1 + 3 * 1)] += Vec3(0.07, -0.05, 0.04);  // the centre vertex
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (int degree : {2, 3}) {
    auto body = makeBody(degree, mesh);
    Mat3 A = Quat(Eigen::AngleAxisd(1.1, Vec3(1, 2, 3).normalized())).toRotationMatrix();
    Mat3 strain = Mat3::Identity();
    for (int i = 0; i < 9; ++i) strain(i / 3, i % 3) += u(rng);
    A = A * strain;
    const Array<double>& X = body->restPositions();
    std::vector<double> x(X.size());
    for (size_t i = 0; i < X.size() / 3; ++i) {
      const Vec3 p = A * Vec3(X[3 * i], X[3 * i + 1], X[3 * i + 2]) + Vec3(0.5, 1, -2);
      for (int k = 0; k < 3; ++k) x[3 * i + k] = p[k];
    }
    ASSERT_EQ(body->setPositions(x.data(), static_cast<int64_t>(x.size())), Status::Ok);
    auto tasks = TaskSystem::create(TaskHooks{}, 2);
    Array<double> f;
    body->elasticForces(*tasks, &f);
    double interior = 0.0, boundary = 0.0;
    for (int32_t i = 0; i < body->nodeCount(); ++i) {
      const Vec3 Xi(X[3 * i], X[3 * i + 1], X[3 * i + 2]);
      const bool onBoundary = (Xi.array() < 1e-12).any() || (Xi.array() > 1.0 - 1e-12).any();
      const double fi = Vec3(f[3 * i], f[3 * i + 1], f[3 * i + 2]).norm();
      double& worst = onBoundary ? boundary : interior;
      worst = std::max(worst, fi);
    }
    EXPECT_GT(boundary, 1.0) << degree;
    EXPECT_LT(interior, 1e-9 * boundary) << "degree " << degree;
    // And a rigid motion gives no force at all.
    for (size_t i = 0; i < X.size() / 3; ++i) {
      const Vec3 p = Quat(Eigen::AngleAxisd(2.5, Vec3(0, 1, 1).normalized())) * Vec3(X[3 * i], X[3 * i + 1], X[3 * i + 2]);
      for (int k = 0; k < 3; ++k) x[3 * i + k] = p[k] + 3.0;
    }
    body->setPositions(x.data(), static_cast<int64_t>(x.size()));
    body->elasticForces(*tasks, &f);
    double maxForce = 0.0;
    for (double v : f) maxForce = std::max(maxForce, std::abs(v));
    EXPECT_LT(maxForce, 1e-6) << "degree " << degree;
  }
}

TEST(HigherOrderElements, PinningAFacesVerticesPinsItsControlPoints) {
  auto body = makeBody(3, makeBoxTetMesh({2, 1, 1}, Vec3(2, 1, 1), Vec3::Zero()));
  std::vector<int32_t> left;
  for (int32_t i = 0; i < 12; ++i)  // the 12 box vertices come first
    if (body->restPositions()[3 * i] == 0.0) left.push_back(i);
  ASSERT_EQ(left.size(), 4u);
  body->setPinned(left.data(), static_cast<int64_t>(left.size()), true);
  int pinnedOnFace = 0, faceNodes = 0;
  for (int32_t i = 0; i < body->nodeCount(); ++i) {
    const bool onFace = body->restPositions()[3 * i] == 0.0;
    faceNodes += onFace;
    pinnedOnFace += onFace && body->pinned(i);
    if (!onFace) {
      EXPECT_FALSE(body->pinned(i)) << i;
    }
  }
  EXPECT_GT(faceNodes, 4);
  EXPECT_EQ(pinnedOnFace, faceNodes);
}

// The reason for higher order: linear tets lock in bending on coarse meshes; quadratic and
// cubic much less. Slender beam (8 x 1 x 1 m) on 8 x 2 x 2 cubes (192 tets).
TEST(HigherOrderElements, CoarseCantileverLockingIsRelievedByHigherOrder) {
  std::printf("\n  cantilever 8x1x1 m on 8x2x2 cubes (192 tets), self-weight\n");
  std::printf("  %-6s %-8s %14s %14s %9s\n", "nu", "degree", "tip [m]", "analytic [m]", "error");
  for (double nu : {0.3, 0.49}) {
    Beam beam;
    beam.nu = nu;
    const double analytic = beam.analyticTipDeflection();
    double error[4] = {0, 0, 0, 0};
    for (int degree : {1, 2, 3}) {
      const double tip = staticTipDeflection(beam, degree, 8, 2, nullptr);
      error[degree] = std::abs(tip - analytic) / analytic;
      std::printf("  %-6.2f %-8d %14.6e %14.6e %8.2f%%\n", nu, degree, tip, analytic, 100 * error[degree]);
    }
    EXPECT_GT(error[1], 0.20) << "linear tets should lock here (nu " << nu << ")";
    if (nu < 0.4) {
      // Issue 6's target at ν = 0.3: quadratic within 3%, cubic at least as good (0.5% slack
      // for beam theory's own approximation of the 3D clamp).
      EXPECT_LT(error[2], 0.03);
      EXPECT_LE(error[3], error[2] + 0.005);
    } else {
      // Near-incompressible: 14.8% (quadratic) and 6.1% (cubic) off beam theory here. Part of
      // that is not discretization: see NearIncompressibleCantileverAgainstA3DReference. What
      // is asserted against beam theory is the locking relief: linear is off by ~90%, higher
      // order by a small fraction of that.
      EXPECT_LT(error[2], 0.25 * error[1]);
      EXPECT_LT(error[3], 0.10 * error[1]);
      EXPECT_LT(error[3], error[2]);
    }
  }
}

// Is beam theory the right reference at ν = 0.49? Its clamp leaves the root section free to
// contract laterally; the 3D clamp (every root node pinned) does not, and near the root the
// material then behaves like a laterally constrained one, stiffer by up to 1/(1 − ν²): 1.10 at
// ν = 0.3 but 1.32 at ν = 0.49, in the region of the largest bending moment. Converged cubic
// solutions of the clamped 3D problem (8x2x2 -> 32x8x8 cubes, extrapolated at the observed
// order ~1.75) lie 1.1% below beam theory at ν = 0.3 and 3.2% below at ν = 0.49. So the right
// yardstick for discretization error is the 3D problem; here it is the cubic solution on
// 16x4x4 cubes, itself within 0.9% of the extrapolated limit (computed once with 24x6x6 and
// 32x8x8, too slow to repeat in a test).
// Measured on 8x2x2: cubic 2.1% below that reference (2.9% below the extrapolated limit):
// within issue 6's 5%. Quadratic: 11% below it (12% below the limit) — quadratic tets still
// carry volumetric stiffness at λ/μ ≈ 50 on a 2-cube-deep section (7.0% on 16x4x4, 5.2% on
// 24x6x6 against beam theory); that is reported, not asserted away.
TEST(HigherOrderElements, NearIncompressibleCantileverAgainstA3DReference) {
  Beam beam;
  beam.nu = 0.49;
  const double analytic = beam.analyticTipDeflection();
  const double reference = staticTipDeflection(beam, 3, 16, 4, nullptr);
  const double quadratic = staticTipDeflection(beam, 2, 8, 2, nullptr);
  const double cubic = staticTipDeflection(beam, 3, 8, 2, nullptr);
  std::printf("\n  nu = 0.49 cantilever, 8x2x2 cubes, against the cubic 16x4x4 solution of the clamped 3D problem\n");
  std::printf("  3D reference %.6e m, beam theory %.6e m (reference %.2f%% stiffer)\n", reference, analytic,
              100 * (analytic - reference) / analytic);
  const double errorQuadratic = std::abs(quadratic - reference) / reference;
  const double errorCubic = std::abs(cubic - reference) / reference;
  std::printf("  quadratic %.6e m: %.2f%% off the reference; cubic %.6e m: %.2f%%\n", quadratic,
              100 * errorQuadratic, cubic, 100 * errorCubic);
  EXPECT_LT(reference, analytic) << "the 3D clamp should be stiffer than beam theory's";
  EXPECT_LT(errorCubic, 0.05);
  EXPECT_LT(errorCubic, errorQuadratic);
}

}  // namespace
}  // namespace vp
