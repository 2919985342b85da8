// Node tables, combinatorial factors and cross-tet node identity of BB elements.
#include "deform/bb_multi_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <set>
#include <tuple>
#include <vector>

namespace vp {
namespace {

TEST(DeformBBMultiIndex, NodeCountsAre4_10_20) {
  EXPECT_EQ(bbNodeCount(1), 4);
  EXPECT_EQ(bbNodeCount(2), 10);
  EXPECT_EQ(bbNodeCount(3), 20);
  EXPECT_EQ(bbMultiIndices(0), nullptr);
  EXPECT_EQ(bbMultiIndices(4), nullptr);
}

TEST(DeformBBMultiIndex, TablesAreCompleteDistinctAndRoundTrip) {
  for (int n = 1; n <= 3; ++n) {
    const BBMultiIndex* t = bbMultiIndices(n);
    std::set<std::tuple<int, int, int, int>> seen;
    for (int k = 0; k < bbNodeCount(n); ++k) {
      EXPECT_EQ(t[k].a[0] + t[k].a[1] + t[k].a[2] + t[k].a[3], n) << "n=" << n << " k=" << k;
      seen.insert({t[k].a[0], t[k].a[1], t[k].a[2], t[k].a[3]});
      const int alpha[4] = {t[k].a[0], t[k].a[1], t[k].a[2], t[k].a[3]};
      EXPECT_EQ(bbNodeIndex(alpha), k);
    }
    // Distinct entries with |α| = n and as many as there are multi-indices: all of them.
    EXPECT_EQ(static_cast<int>(seen.size()), bbNodeCount(n));
  }
  const int negative[4] = {-1, 2, 0, 0};
  const int tooHigh[4] = {4, 0, 0, 0};
  const int zero[4] = {0, 0, 0, 0};
  EXPECT_EQ(bbNodeIndex(negative), -1);
  EXPECT_EQ(bbNodeIndex(tooHigh), -1);
  EXPECT_EQ(bbNodeIndex(zero), -1);
}

TEST(DeformBBMultiIndex, OrderIsVerticesThenEdgesThenFaces) {
  for (int n = 1; n <= 3; ++n) {
    const BBMultiIndex* t = bbMultiIndices(n);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(t[i].a[i], n) << "vertex node " << i;
    int lastCount = 1;
    for (int k = 0; k < bbNodeCount(n); ++k) {
      BBNodeSupport s;
      ASSERT_EQ(bbNodeSupport(n, k, &s), Status::Ok);
      EXPECT_GE(s.count, lastCount) << "support sizes must not decrease along the order";
      lastCount = s.count;
    }
  }
  // Edge order (0,1) (0,2) (0,3) (1,2) (1,3) (2,3), cubic edge nodes from first vertex on.
  const int cubicEdge01First[4] = {2, 1, 0, 0};
  const int cubicEdge23Second[4] = {0, 0, 1, 2};
  const int quadEdge13[4] = {0, 1, 0, 1};
  const int cubicFace023[4] = {1, 0, 1, 1};
  EXPECT_EQ(bbNodeIndex(cubicEdge01First), 4);
  EXPECT_EQ(bbNodeIndex(cubicEdge23Second), 15);
  EXPECT_EQ(bbNodeIndex(quadEdge13), 8);
  EXPECT_EQ(bbNodeIndex(cubicFace023), 18);
}

TEST(DeformBBMultiIndex, MultinomialsSumToFourToTheN) {
  // Σ_α n!/α! = (1+1+1+1)^n: the multinomial theorem; catches a wrong coefficient.
  for (int n = 1; n <= 3; ++n) {
    double sum = 0.0;
    for (int k = 0; k < bbNodeCount(n); ++k) sum += bbMultinomial(bbMultiIndices(n)[k]);
    EXPECT_EQ(sum, std::pow(4.0, n));
  }
  EXPECT_EQ(bbMultinomial(BBMultiIndex{{1, 1, 1, 0}}), 6.0);
  EXPECT_EQ(bbBinomial(9, 3), 84.0);
  EXPECT_EQ(bbBinomial(3, 4), 0.0);
}

TEST(DeformBBMultiIndex, GramFactorRowSumsMatchBasisIntegral) {
  // Σ_β ∫B_α B_β = ∫B_α = V/C(n+3,3), so Σ_β G_n(α,β) = C(2n+3,3)/C(n+3,3) for every α.
  // The factors are ratios of small integers, so 1e-14 relative leaves only round-off.
  for (int n = 1; n <= 3; ++n) {
    const BBMultiIndex* t = bbMultiIndices(n);
    const double expected = bbBinomial(2 * n + 3, 3) / bbBinomial(n + 3, 3);
    for (int i = 0; i < bbNodeCount(n); ++i) {
      double sum = 0.0;
      for (int j = 0; j < bbNodeCount(n); ++j) {
        sum += bbGramFactor(t[i], t[j]);
        EXPECT_EQ(bbGramFactor(t[i], t[j]), bbGramFactor(t[j], t[i]));
      }
      EXPECT_NEAR(sum, expected, 1e-14 * expected) << "n=" << n << " node " << i;
    }
  }
}

TEST(DeformBBMultiIndex, SupportRejectsBadArguments) {
  BBNodeSupport s;
  EXPECT_EQ(bbNodeSupport(0, 0, &s), Status::InvalidArgument);
  EXPECT_EQ(bbNodeSupport(2, 10, &s), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("node = 10"), std::string::npos) << lastError();
  const std::int32_t repeated[4] = {3, 5, 3, 7};
  BBNodeKey key;
  EXPECT_EQ(bbNodeKey(2, 0, repeated, &key), Status::InvalidArgument);
}

// Two tets sharing the face {10, 20, 30} with the shared vertices in different local
// positions and orientations; the fourth vertices are 40 and 50.
TEST(DeformBBMultiIndex, NodeKeysAgreeAcrossNeighbouringTets) {
  const std::int32_t tetA[4] = {10, 20, 30, 40};
  const std::int32_t tetB[4] = {50, 30, 10, 20};
  for (int n = 1; n <= 3; ++n) {
    const int count = bbNodeCount(n);
    std::vector<BBNodeKey> keysA(count), keysB(count);
    for (int k = 0; k < count; ++k) {
      ASSERT_EQ(bbNodeKey(n, k, tetA, &keysA[k]), Status::Ok);
      ASSERT_EQ(bbNodeKey(n, k, tetB, &keysB[k]), Status::Ok);
    }
    // Within a tet every node has its own key.
    for (int i = 0; i < count; ++i)
      for (int j = i + 1; j < count; ++j) {
        EXPECT_NE(keysA[i], keysA[j]);
        EXPECT_NE(keysB[i], keysB[j]);
      }
    // A node is shared iff it lies on the common face (no vertex 40 / 50 in its support),
    // and then exactly one node of the other tet has its key, at the same position.
    const BBMultiIndex* t = bbMultiIndices(n);
    int shared = 0;
    for (int i = 0; i < count; ++i) {
      const bool onFace = t[i].a[3] == 0;  // local vertex 3 of A is 40
      int matches = 0;
      for (int j = 0; j < count; ++j) {
        if (keysA[i] != keysB[j]) continue;
        ++matches;
        // Same point: Σ α_i · vertex id is a position proxy independent of local order.
        double pa = 0, pb = 0;
        for (int v = 0; v < 4; ++v) {
          pa += t[i].a[v] * tetA[v];
          pb += t[j].a[v] * tetB[v];
        }
        EXPECT_EQ(pa, pb);
      }
      EXPECT_EQ(matches, onFace ? 1 : 0) << "n=" << n << " node " << i;
      shared += matches;
    }
    EXPECT_EQ(shared, (n + 1) * (n + 2) / 2);  // nodes on a triangle of degree n
  }
}

TEST(DeformBBMultiIndex, CubicEdgeSlotsFollowGlobalOrder) {
  // Edge (10, 20) seen as local (0,1) in one tet and (1,0) in the other: the node nearer
  // global vertex 10 has exponents (2,1) and slot 0 in both.
  const std::int32_t forward[4] = {10, 20, 30, 40};
  const std::int32_t backward[4] = {20, 10, 30, 40};
  BBNodeKey k1, k2;
  ASSERT_EQ(bbNodeKey(3, 4, forward, &k1), Status::Ok);   // α = (2,1,0,0): near 10
  ASSERT_EQ(bbNodeKey(3, 5, backward, &k2), Status::Ok);  // α = (1,2,0,0): near 10
  EXPECT_EQ(k1, k2);
  EXPECT_EQ(k1.slot, 0);
  EXPECT_EQ(k1.vertices[0], 10);
  EXPECT_EQ(k1.exponents[0], 2);
  ASSERT_EQ(bbNodeKey(3, 5, forward, &k1), Status::Ok);
  EXPECT_EQ(k1.slot, 1);
}

}  // namespace
}  // namespace vp
