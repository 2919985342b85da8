// Multi-indices of Bernstein–Bézier (BB) tetrahedral elements of degree 1, 2, 3 and the
// combinatorial factors that make their matrices analytic.
//
// A degree-n element has one control point (node) per multi-index α = (α0, α1, α2, α3),
// αi >= 0, |α| = n: 4, 10 and 20 nodes for n = 1, 2, 3. Its basis function is
//   B_α(λ) = n! / (α0! α1! α2! α3!) · λ0^α0 λ1^α1 λ2^α2 λ3^α3   (λ barycentric).
//
// Local node order (fixed; element matrices, evaluation and meshes all rely on it):
//   1. the 4 vertex nodes α = n·e_i, i = 0..3 — so the first 4 nodes of any degree are the
//      degree-1 element, and a p-multigrid level or a linear fallback can reuse them;
//   2. edge nodes, edges in the order (0,1) (0,2) (0,3) (1,2) (1,3) (2,3); on edge (i,j)
//      the nodes run from i to j (for n = 3: α_i = 2, α_j = 1 first, then 1, 2);
//   3. face nodes (only n = 3: α = (1,1,1) on a face), faces in the order
//      (0,1,2) (0,1,3) (0,2,3) (1,2,3).
// There are no interior nodes for n <= 3.
//
// Nodes on a shared edge or face must be one global unknown. Local vertex order differs
// between neighbours, so the identity of a node is given in global terms (BBNodeKey): the
// ascending global ids of the vertices it lies on and its exponents in that same order.
#pragma once

#include <cstdint>

#include "core/status.h"

namespace vp {

constexpr int kBBMaxDegree = 3;
constexpr int kBBMaxNodes = 20;  // nodes of a cubic element

// (n+1)(n+2)(n+3)/6: the number of multi-indices with |α| = n (n >= 0).
constexpr int bbNodeCount(int degree) {
  return (degree + 1) * (degree + 2) * (degree + 3) / 6;
}

struct BBMultiIndex {
  std::uint8_t a[4];
};

// The local node table of a degree (1..3) in the order documented above, nodeCount entries.
// Returns nullptr for any other degree.
const BBMultiIndex* bbMultiIndices(int degree);

// Local node index of α in its degree's table (degree = |α|, 1..3), or -1 if α is not a
// valid multi-index of degree 1..3 (a negative entry, or |α| outside 1..3).
int bbNodeIndex(const int alpha[4]);

// Binomial coefficient C(n, k) as a double (0 when k < 0 or k > n); exact for n <= 60.
double bbBinomial(int n, int k);

// n! / (α0! α1! α2! α3!) with n = |α|: the coefficient of B_α.
double bbMultinomial(const BBMultiIndex& alpha);

// G_n(α, β) = Π_i C(αi + βi, αi) / C(2n, n), n = |α| = |β| (the caller guarantees equal
// sizes). ∫_T B^n_α B^n_β dV = V · G_n(α, β) / C(2n + 3, 3).
double bbGramFactor(const BBMultiIndex& alpha, const BBMultiIndex& beta);

// Where a local node sits on the tetrahedron, in local vertex ids.
struct BBNodeSupport {
  int count;        // 1 vertex, 2 edge, 3 face (4 would be interior; none for n <= 3)
  int vertices[4];  // local vertex ids 0..3 with αi > 0, ascending; unused entries -1
};

// Fails with InvalidArgument for a degree outside 1..3 or a node outside 0..nodeCount-1.
Status bbNodeSupport(int degree, int node, BBNodeSupport* support);

// Identity of a node independent of the tet it is seen from. Two tets that share an edge
// or face produce equal keys for their shared nodes and only for those.
struct BBNodeKey {
  int count;                  // vertices the node lies on: 1 vertex, 2 edge, 3 face
  std::int32_t vertices[4];   // their global ids, ascending; unused entries -1
  std::uint8_t exponents[4];  // α at those vertices, same order; unused entries 0
  int slot;                   // position of the node among the nodes strictly inside that
                              // vertex/edge/face, ordered by exponents descending
                              // lexicographically (n = 3 edge (u<v): (2,1) -> 0, (1,2) -> 1)
};

bool operator==(const BBNodeKey& a, const BBNodeKey& b);
inline bool operator!=(const BBNodeKey& a, const BBNodeKey& b) { return !(a == b); }

// globalVertices: the tet's 4 global vertex ids in its local order. Fails with
// InvalidArgument for a bad degree or node, or repeated/negative global ids.
Status bbNodeKey(int degree, int node, const std::int32_t globalVertices[4], BBNodeKey* key);

}  // namespace vp
