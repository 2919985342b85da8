// The p-multigrid levels of a BB mesh: numbering like the actor's, and prolongations that
// are exact degree elevation of the global (continuous) field.
#include "deform/degree_hierarchy.h"

#include <gtest/gtest.h>

#include <random>

#include "deform/bb_evaluation.h"
#include "deform/bb_multi_index.h"
#include "deform/deformable_body.h"
#include "deform_test_util.h"
#include "geometry/box_tet_mesh.h"

namespace vp {
namespace {

TetMesh jitteredBox() {
  TetMesh mesh = makeBoxTetMesh({3, 2, 2}, Vec3(3, 2, 2), Vec3::Zero());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.12, 0.12);
  for (Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      const double hi = k == 0 ? 3.0 : 2.0;  // boundary coordinates stay: the box keeps its faces
      if (v[k] > 1e-9 && v[k] < hi - 1e-9) v[k] += u(rng);
    }
  return mesh;
}

std::unique_ptr<DeformableBody> makeBody(int degree, const TetMesh& mesh) {
  DeformableDesc desc;
  desc.degree = degree;
  desc.mesh = mesh;
  std::unique_ptr<DeformableBody> body;
  EXPECT_EQ(DeformableBody::create(desc, &body), Status::Ok) << lastError();
  return body;
}

std::vector<double> prolongate(const NodeProlongation& P, const std::vector<double>& coarse) {
  std::vector<double> fine(3 * static_cast<size_t>(P.fineNodes), 0.0);
  for (int32_t i = 0; i < P.fineNodes; ++i)
    for (int32_t k = P.rowStart[i]; k < P.rowStart[i + 1]; ++k)
      for (int a = 0; a < 3; ++a) fine[3 * i + a] += P.weights[k] * coarse[3 * P.columns[k] + a];
  return fine;
}

// The field of element e at λ from global coefficients of a level.
Vec3 evaluate(const DegreeLevel& level, const std::vector<double>& field, int64_t e, const double bary[4]) {
  const int N = bbNodeCount(level.degree);
  double coeffs[3 * kBBMaxNodes], value[3];
  for (int a = 0; a < N; ++a)
    for (int k = 0; k < 3; ++k) coeffs[3 * a + k] = field[3 * level.elementNodes[N * e + a] + k];
  bbEvaluate(level.degree, coeffs, bary, value);
  return Vec3(value[0], value[1], value[2]);
}

// A lower level numbers its nodes exactly like an actor created at that degree.
TEST(DegreeHierarchy, LevelsAreNumberedLikeTheActorOfThatDegree) {
  const TetMesh mesh = jitteredBox();
  auto cubic = makeBody(3, mesh), quadratic = makeBody(2, mesh);
  DegreeHierarchy h;
  ASSERT_EQ(buildDegreeHierarchy({3, 2, 1}, cubic->elementNodes().data(), cubic->elementCount(), cubic->nodeCount(), &h),
            Status::Ok);
  ASSERT_EQ(h.levels.size(), 3u);
  EXPECT_EQ(h.levels[1].nodeCount, quadratic->nodeCount());
  EXPECT_TRUE(std::equal(h.levels[1].elementNodes.begin(), h.levels[1].elementNodes.end(),
                         quadratic->elementNodes().begin()));
  EXPECT_EQ(h.levels[2].nodeCount, static_cast<int32_t>(mesh.vertices.size()));
  for (size_t k = 0; k < mesh.tets.size(); ++k)
    for (int a = 0; a < 4; ++a) EXPECT_EQ(h.levels[2].elementNodes[4 * k + a], mesh.tets[k][a]);
}

// Prolongating a random lower-degree field gives, in every element, the same polynomial at
// the higher degree (elevation is exact), for 1 -> 2, 2 -> 3, 1 -> 3 directly, and 1 -> 2 -> 3
// equals 1 -> 3.
TEST(DegreeHierarchy, ProlongationReproducesTheLowerDegreeFieldExactly) {
  const TetMesh mesh = jitteredBox();
  auto cubic = makeBody(3, mesh), quadratic = makeBody(2, mesh);
  DegreeHierarchy h321, h31, h21;
  ASSERT_EQ(buildDegreeHierarchy({3, 2, 1}, cubic->elementNodes().data(), cubic->elementCount(), cubic->nodeCount(), &h321),
            Status::Ok);
  ASSERT_EQ(buildDegreeHierarchy({3, 1}, cubic->elementNodes().data(), cubic->elementCount(), cubic->nodeCount(), &h31),
            Status::Ok);
  ASSERT_EQ(buildDegreeHierarchy({2, 1}, quadratic->elementNodes().data(), quadratic->elementCount(),
                                 quadratic->nodeCount(), &h21),
            Status::Ok);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto randomField = [&](int32_t nodes) {
    std::vector<double> f(3 * static_cast<size_t>(nodes));
    for (double& v : f) v = u(rng);
    return f;
  };
  const std::vector<double> linear = randomField(h321.levels[2].nodeCount);
  const std::vector<double> quad = randomField(h321.levels[1].nodeCount);
  const std::vector<double> linearAt2 = prolongate(h321.prolongations[1], linear);
  const std::vector<double> linearAt3 = prolongate(h321.prolongations[0], linearAt2);
  const std::vector<double> linearAt3Direct = prolongate(h31.prolongations[0], linear);
  const std::vector<double> quadAt3 = prolongate(h321.prolongations[0], quad);
  const std::vector<double> linearAt2Of21 = prolongate(h21.prolongations[0], linear);
  for (size_t k = 0; k < linearAt3.size(); ++k) EXPECT_NEAR(linearAt3[k], linearAt3Direct[k], 1e-14);
  for (size_t k = 0; k < linearAt2.size(); ++k) EXPECT_NEAR(linearAt2[k], linearAt2Of21[k], 1e-14);
  for (int64_t e = 0; e < cubic->elementCount(); ++e)
    for (int trial = 0; trial < 4; ++trial) {
      double bary[4];
      deform_test::randomBary(rng, bary);
      const Vec3 l1 = evaluate(h321.levels[2], linear, e, bary);
      EXPECT_LT((evaluate(h321.levels[1], linearAt2, e, bary) - l1).norm(), 1e-13);
      EXPECT_LT((evaluate(h321.levels[0], linearAt3, e, bary) - l1).norm(), 1e-13);
      EXPECT_LT((evaluate(h321.levels[0], quadAt3, e, bary) - evaluate(h321.levels[1], quad, e, bary)).norm(), 1e-13);
    }
}

TEST(DegreeHierarchy, RejectsDegreesThatDoNotDecrease) {
  const TetMesh mesh = jitteredBox();
  auto cubic = makeBody(3, mesh);
  DegreeHierarchy h;
  for (const std::vector<int>& bad : {std::vector<int>{3, 3}, std::vector<int>{3, 0}, std::vector<int>{4, 1},
                                      std::vector<int>{}})
    EXPECT_EQ(buildDegreeHierarchy(bad, cubic->elementNodes().data(), cubic->elementCount(), cubic->nodeCount(), &h),
              Status::InvalidArgument);
}

}  // namespace
}  // namespace vp
