// The stencils of isosurface stuffing (Labelle & Shewchuk 2007): how one tetrahedron of the
// BCC lattice is filled once its vertices are inside (+), on the surface (0: warped there)
// or outside (-) and its +- edges carry cut points. The filled part is the hull of its +
// and 0 vertices and its cut points: one tet, a pyramid (two tets) or a triangular prism
// (three tets).
//
// Conformity: a quadrilateral that lies on a lattice face (two + vertices, one -) is split
// by a rule that depends on that face alone, so the two lattice tets sharing it split it
// alike. When its + vertices are joined by a long edge the face is symmetric and the parity
// rule decides: the diagonal touches the + vertex whose lattice index along that edge's axis
// is even. Otherwise the diagonal runs from the + vertex whose edge to the - vertex is short
// to the cut point on the long edge. Neither rule can make a prism's three diagonals cyclic,
// so no prism needs an extra vertex; a prism's quadrilateral inside the lattice tet (case
// ++--) is free and takes the shorter diagonal that keeps the three acyclic.
#pragma once

#include "core/allocator.h"
#include "geometry/bcc_lattice.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace vp {

struct StencilTet {
  std::array<LatticePoint, 4> lattice{};  // the lattice vertices (for the face rules)
  std::array<int8_t, 4> sign{};            // +1 inside, 0 on the surface, -1 outside
  std::array<int32_t, 4> vertex{};         // output vertex of each corner that is not outside
  // cut[i][j], sign[i] = +1 and sign[j] = -1: the output vertex of the cut point on edge ij.
  std::array<std::array<int32_t, 4>, 4> cut{};
};

// Appends the tets that fill the inside part of `tet` to `out`, each positively oriented at
// `positions` (indexed by output vertex). A tet with no + vertex adds nothing. Returns false
// only if a prism's diagonals were cyclic, which the rules above exclude.
bool fillStencil(const StencilTet& tet, const Array<Eigen::Vector3d>& positions, Array<std::array<int32_t, 4>>* out);

}  // namespace vp
