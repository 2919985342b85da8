// The last step of isosurface stuffing: the stuffed mesh's boundary triangles are chords of the
// surface (their corners lie on it), so a curved part loses the volume between each chord and
// the surface, in proportion to (cell / thickness)^2. This step moves the boundary vertices
// along their normals so that, to first order, each boundary triangle's lost (or, where the
// surface is concave, gained) volume is given back.
//
// The rule. For each boundary triangle f (area A_f, unit outward normal n_f) the mean gap g_f
// between it and the surface along n_f is measured at its three edge midpoints (the gap is
// zero at the corners; over a triangle inscribed in a smooth surface it is quadratic, and the
// edge-midpoint rule integrates a quadratic exactly): signed, positive where the surface lies
// outside the triangle, the nearest crossing within kOffsetReachCells cells either way. Each
// boundary vertex v takes a third of each of its triangles' volume A_f g_f and moves along its
// area-weighted normal N_v = sum A_f n_f by s_v = sum A_f g_f / |N_v|: moving v by s_v N_v / |N_v|
// changes the mesh's volume by s_v |N_v| / 3 to first order, so the moves give back the sum of
// A_f g_f, the volume between the chords and the surface. |s_v| is capped at kMaxOffsetCells
// cells (where N_v nearly cancels, at the tip of a part thinner than a cell).
//
// The guarantees stay. The vertices are moved one at a time, in mesh order; a move that would
// leave one of the vertex's tets non-positive, with a dihedral angle outside
// [kStuffingMinDihedralDegrees, kStuffingMaxDihedralDegrees], or past the narrower
// [kOffsetMinDihedralDegrees, kOffsetMaxDihedralDegrees] when the tet was inside those before,
// or further past them when it was not, is halved, up to kOffsetHalvings times, then dropped
// (the vertex stays on the surface). Each tet is checked at its final shape when its last
// moved vertex is placed, so no move leaves a tet non-positive or outside the bounds. The
// narrower range keeps the offset from becoming what sets the mesh's worst angle: without it
// the moves crowd the worst tets up to the paper's bounds; with it they give back nearly the
// same volume. Deterministic.
//
// Limits: a part the lattice lost (no lattice vertex inside it) is not given back; at a sharp
// edge the lost wedge is given back by vertices moving off the flat faces beside it; two parts
// of the surface closer than the moves (a fraction of a cell) may overlap.
#pragma once

#include "geometry/refit_bvh.h"
#include "geometry/surface_mesh.h"
#include "geometry/tet_mesh.h"

#include <cstdint>

namespace vp {

constexpr double kOffsetReachCells = 1.0;   // how far a gap is looked for along a normal
constexpr double kMaxOffsetCells = 0.5;     // the largest move of a boundary vertex
constexpr int kOffsetHalvings = 4;          // halvings of a move that breaks a bound before it is dropped
// A tet inside these may be worsened up to them, one outside them not at all. About where the
// stuffing's own worse tets lie, well inside the paper's bounds: a narrower range starts to
// refuse the moves on smooth shapes, a wider one lets the moves set the mesh's worst angle.
constexpr double kOffsetMinDihedralDegrees = 20.0;
constexpr double kOffsetMaxDihedralDegrees = 140.0;

struct StuffingOffsetReport {
  int64_t movedVertices = 0;    // boundary vertices moved (by their whole move or part of it)
  int64_t limitedVertices = 0;  // vertices whose move was halved or dropped by an angle check
  double maxOffset = 0.0;       // the largest move, in cells
};

// `mesh`: a stuffing of `surface` (bvh built over it) with lattice spacing `h`, every tet
// positive; `onSurface`: per mesh vertex, 1 for a cut point or a warped lattice vertex. Moves
// its boundary vertices by the rule above; `report` may be null.
void offsetStuffedBoundary(const SurfaceMesh& surface, const RefitBvh& bvh, double h, const Array<uint8_t>& onSurface,
                           TetMesh* mesh, StuffingOffsetReport* report = nullptr);

}  // namespace vp
