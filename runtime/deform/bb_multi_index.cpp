#include "deform/bb_multi_index.h"

#include <algorithm>

namespace vp {
namespace {

// Written out rather than generated: the tables are the documentation of the node order
// and can be placed in GPU constant memory as they are.
constexpr BBMultiIndex kLinear[4] = {
    {{1, 0, 0, 0}}, {{0, 1, 0, 0}}, {{0, 0, 1, 0}}, {{0, 0, 0, 1}}};

constexpr BBMultiIndex kQuadratic[10] = {
    {{2, 0, 0, 0}}, {{0, 2, 0, 0}}, {{0, 0, 2, 0}}, {{0, 0, 0, 2}},
    // edges (0,1) (0,2) (0,3) (1,2) (1,3) (2,3)
    {{1, 1, 0, 0}}, {{1, 0, 1, 0}}, {{1, 0, 0, 1}},
    {{0, 1, 1, 0}}, {{0, 1, 0, 1}}, {{0, 0, 1, 1}}};

constexpr BBMultiIndex kCubic[20] = {
    {{3, 0, 0, 0}}, {{0, 3, 0, 0}}, {{0, 0, 3, 0}}, {{0, 0, 0, 3}},
    // edges, each from its first vertex to its second
    {{2, 1, 0, 0}}, {{1, 2, 0, 0}},  // (0,1)
    {{2, 0, 1, 0}}, {{1, 0, 2, 0}},  // (0,2)
    {{2, 0, 0, 1}}, {{1, 0, 0, 2}},  // (0,3)
    {{0, 2, 1, 0}}, {{0, 1, 2, 0}},  // (1,2)
    {{0, 2, 0, 1}}, {{0, 1, 0, 2}},  // (1,3)
    {{0, 0, 2, 1}}, {{0, 0, 1, 2}},  // (2,3)
    // faces (0,1,2) (0,1,3) (0,2,3) (1,2,3)
    {{1, 1, 1, 0}}, {{1, 1, 0, 1}}, {{1, 0, 1, 1}}, {{0, 1, 1, 1}}};

double factorial(int n) {
  double f = 1.0;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

bool validNode(int degree, int node) {
  return degree >= 1 && degree <= kBBMaxDegree && node >= 0 && node < bbNodeCount(degree);
}

// Rank of `e` (count entries, all >= 1, summing to n) among all such tuples ordered
// descending lexicographically. Enumerates: there are at most 2 candidates for n <= 3.
int interiorSlot(const std::uint8_t* e, int count, int n) {
  int rank = 0;
  int candidate[4] = {0, 0, 0, 0};
  // Odometer over the first count-1 entries, each from high to low; the last is implied.
  const int top = n - (count - 1);  // the largest value any one entry can take
  for (int i = 0; i < count - 1; ++i) candidate[i] = top;
  for (;;) {
    int sum = 0;
    for (int i = 0; i < count - 1; ++i) sum += candidate[i];
    const int last = n - sum;
    if (last >= 1) {
      candidate[count - 1] = last;
      bool equal = true;
      for (int i = 0; i < count; ++i) equal = equal && candidate[i] == e[i];
      if (equal) return rank;
      ++rank;
    }
    int i = count - 2;
    while (i >= 0 && candidate[i] == 1) {
      candidate[i] = top;
      --i;
    }
    if (i < 0) return -1;
    --candidate[i];
  }
}

}  // namespace

const BBMultiIndex* bbMultiIndices(int degree) {
  switch (degree) {
    case 1: return kLinear;
    case 2: return kQuadratic;
    case 3: return kCubic;
    default: return nullptr;
  }
}

int bbNodeIndex(const int alpha[4]) {
  int n = 0;
  for (int i = 0; i < 4; ++i) {
    if (alpha[i] < 0) return -1;
    n += alpha[i];
  }
  const BBMultiIndex* table = bbMultiIndices(n);
  if (table == nullptr) return -1;
  for (int k = 0; k < bbNodeCount(n); ++k) {
    if (table[k].a[0] == alpha[0] && table[k].a[1] == alpha[1] && table[k].a[2] == alpha[2] &&
        table[k].a[3] == alpha[3])
      return k;
  }
  return -1;
}

double bbBinomial(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  double c = 1.0;
  // Multiply then divide keeps every intermediate an exact integer.
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

double bbMultinomial(const BBMultiIndex& alpha) {
  const int n = alpha.a[0] + alpha.a[1] + alpha.a[2] + alpha.a[3];
  return factorial(n) / (factorial(alpha.a[0]) * factorial(alpha.a[1]) *
                         factorial(alpha.a[2]) * factorial(alpha.a[3]));
}

double bbGramFactor(const BBMultiIndex& alpha, const BBMultiIndex& beta) {
  const int n = alpha.a[0] + alpha.a[1] + alpha.a[2] + alpha.a[3];
  double g = 1.0;
  for (int i = 0; i < 4; ++i) g *= bbBinomial(alpha.a[i] + beta.a[i], alpha.a[i]);
  return g / bbBinomial(2 * n, n);
}

Status bbNodeSupport(int degree, int node, BBNodeSupport* support) {
  if (degree < 1 || degree > kBBMaxDegree)
    return fail(Status::InvalidArgument, "bbNodeSupport: degree = %d, expected 1, 2 or 3", degree);
  if (!validNode(degree, node))
    return fail(Status::InvalidArgument, "bbNodeSupport: node = %d, expected 0..%d for degree %d",
                node, bbNodeCount(degree) - 1, degree);
  const BBMultiIndex& alpha = bbMultiIndices(degree)[node];
  support->count = 0;
  for (int i = 0; i < 4; ++i) support->vertices[i] = -1;
  for (int i = 0; i < 4; ++i)
    if (alpha.a[i] > 0) support->vertices[support->count++] = i;
  return Status::Ok;
}

bool operator==(const BBNodeKey& a, const BBNodeKey& b) {
  if (a.count != b.count || a.slot != b.slot) return false;
  for (int i = 0; i < 4; ++i)
    if (a.vertices[i] != b.vertices[i] || a.exponents[i] != b.exponents[i]) return false;
  return true;
}

Status bbNodeKey(int degree, int node, const std::int32_t globalVertices[4], BBNodeKey* key) {
  BBNodeSupport support;
  if (Status s = bbNodeSupport(degree, node, &support); s != Status::Ok)
    return addErrorContext(s, "bbNodeKey");
  for (int i = 0; i < 4; ++i) {
    if (globalVertices[i] < 0)
      return fail(Status::InvalidArgument, "bbNodeKey: globalVertices[%d] = %d is negative", i,
                  globalVertices[i]);
    for (int j = 0; j < i; ++j)
      if (globalVertices[i] == globalVertices[j])
        return fail(Status::InvalidArgument,
                    "bbNodeKey: globalVertices[%d] = globalVertices[%d] = %d (degenerate tet)", j,
                    i, globalVertices[i]);
  }
  const BBMultiIndex& alpha = bbMultiIndices(degree)[node];
  // Sort the supporting local vertices by global id; the exponents follow their vertex.
  int order[4];
  for (int i = 0; i < support.count; ++i) order[i] = support.vertices[i];
  // Insertion sort of at most 4 entries (std::sort on a 4-array trips a GCC 12 -Warray-bounds
  // false positive, and this is as fast for 4).
  for (int i = 1; i < support.count; ++i)
    for (int j = i; j > 0 && globalVertices[order[j]] < globalVertices[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
  key->count = support.count;
  for (int i = 0; i < 4; ++i) {
    key->vertices[i] = i < support.count ? globalVertices[order[i]] : -1;
    key->exponents[i] = i < support.count ? alpha.a[order[i]] : 0;
  }
  key->slot = interiorSlot(key->exponents, support.count, degree);
  if (key->slot < 0)
    return fail(Status::Internal, "bbNodeKey: no slot for node %d of degree %d", node, degree);
  return Status::Ok;
}

}  // namespace vp
