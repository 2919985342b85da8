// Which nodes of one cell's 8 x 8 x 8 lattice lie outside a closed triangle mesh, by counting
// the mesh's crossings along the lattice's lines instead of a signed distance per node.
//
// Why. The split cut-cell pass (fluid/solids/cut_cell_components.h) needs the sign of every
// lattice node of a cut cell. With a mesh, a signed distance costs a nearest-triangle search
// and a ray-parity walk through the whole mesh, and a cell the surface passes through needs
// it at a few hundred nodes: a deformable's boundary, recomputed every fluid step, made that
// pass most of the tank's fraction time. Crossings along lines need one ray-parity test per
// cell and a handful of line-triangle tests per line (a few dozen lines).
//
// How. Node (a, b, c) sits at origin + h * (cell + (a, b, c) / 7), bitwise as the pass places
// it. The sign of node (0, 0, 0) is the mesh's ray parity (the test the signed distance uses);
// each further node's sign flips once per crossing of the mesh between it and a node of known
// sign along a lattice line: the z-line through (0, 0), then the y-lines at a = 0, then the
// x-lines. For a closed mesh the parity of crossings along a path depends on its ends only,
// so this gives the same signs as a signed distance at each node. Where a line passes within
// a tolerance of a triangle's edge, lies nearly in its plane, or crosses it near a node (a
// node on the surface: not open there), the crossings do not decide and the function says so;
// the caller then samples the signed distance as before. (geometry/row_parity_inside.h counts
// crossings for a whole grid too, but with its own positions and either answer on the surface.)
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "collide/face_coverage.h"

namespace vp {

// Bit a + 8 b of outside[c] is set where node (a, b, c) lies outside `mesh` (a prepared
// triangle-mesh collider; a deforming surface included) and not on it. Returns false, with
// `outside` unspecified, when the crossings do not decide (see above).
bool latticeNodesOutsideMesh(const PreparedCollider& mesh, const Eigen::Vector3d& origin, double h,
                             const Eigen::Vector3d& cell, std::array<uint64_t, 8>* outside);

}  // namespace vp
