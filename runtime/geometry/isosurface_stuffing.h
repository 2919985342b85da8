// Builds a simulation mesh that keeps a closed surface's volume: isosurface stuffing
// (Labelle & Shewchuk, "Isosurface Stuffing: Fast Tetrahedral Meshes with Good Dihedral
// Angles", SIGGRAPH 2007) on a uniform body-centred cubic lattice, with the surface itself as
// the isosurface. Lattice vertices are classified inside or outside, every lattice edge
// between the two gets a cut point where it meets the surface, lattice vertices too close to
// a cut point are warped onto it, and each lattice tet is filled by a stencil
// (stuffing_stencils.h). The mesh's boundary is then a triangulation of points on the surface
// whose triangles are chords of it, so curved parts lose volume (second order in the lattice
// spacing, large for parts a few cells thick); by default the boundary vertices are then moved
// off the surface to give that volume back (stuffing_offset.h). Features thinner than the
// spacing may be lost, which no offset restores. With `grading` > 0 the lattice is octree-graded
// (graded_bcc_lattice.h): finest near the surface, up to 2^grading times coarser deep inside.
#pragma once

#include "core/status.h"
#include "geometry/graded_bcc_lattice.h"
#include "geometry/stuffing_offset.h"
#include "geometry/surface_grid.h"
#include "geometry/surface_mesh.h"
#include "geometry/tet_mesh.h"

#include <cstdint>

namespace vp {

// The warp thresholds of the paper for the uniform lattice, as fractions of the edge length
// (long edges: the cube's size h; short ones: h sqrt(3) / 2), and the dihedral angle bounds
// (degrees) they prove for every output tet.
constexpr double kStuffingAlphaLong = 0.24999;
constexpr double kStuffingAlphaShort = 0.41189;
constexpr double kStuffingMinDihedralDegrees = 10.7;
constexpr double kStuffingMaxDihedralDegrees = 164.8;
// The graded lattice (graded_bcc_lattice.h) keeps the same bounds: the surface's side is the
// uniform lattice's, and the tets inside are pieces of octahedra and pyramids between cube
// centres and face points, whose angles (enumerated over every way a face's edges can be split:
// docs/choices.md) lie well inside these. The paper's own graded construction, with its own
// thresholds and bounds, is not the one built here.
constexpr double kGradedStuffingMinDihedralDegrees = kStuffingMinDihedralDegrees;
constexpr double kGradedStuffingMaxDihedralDegrees = kStuffingMaxDihedralDegrees;

struct StuffingReport {
  SurfaceGrid grid;             // the cubes; the lattice adds one cube of margin on every side
  int64_t insideVertices = 0;   // lattice vertices inside the surface
  int64_t cutPoints = 0;        // cut points kept (on edges whose ends were not warped)
  int64_t warpedVertices = 0;   // lattice vertices moved onto a cut point
  int64_t missedCuts = 0;       // inside-outside edges lying in a surface triangle's plane: cut at the midpoint
  StuffingOffsetReport offset;  // the boundary's move (KeepVolume)
};

// Where the boundary vertices end up: on the surface (the paper's mesh: its boundary
// triangles are chords, so curved parts lose volume), or moved off it by the rule of
// stuffing_offset.h so that the chords' lost volume is given back (the default).
enum class StuffingBoundary { OnSurface, KeepVolume };

// `resolution`: lattice cells along the longest axis of the surface's bounding box, with the
// same meaning and bounds as tetrahedralizeVoxels (surface_grid.h: 1..1024, at most 2^24
// cells). `surface`: closed and outward-oriented (counter-clockwise seen from outside);
// inside means odd ray parity (row_parity_inside.h).
// Guarantees: every tet positively oriented; conforming (neighbouring tets share whole faces
// and their vertices); with OnSurface every boundary vertex on the surface (a cut point, or a
// lattice vertex warped onto one; an edge lying in a surface triangle's plane is cut at its
// midpoint, which is on the surface too), with KeepVolume within kMaxOffsetCells cells of it
// (the same tets, boundary vertices moved); deterministic output (lattice vertices in lattice
// order, then cut points in the order of their edges). The mesh may be empty when no lattice
// vertex is inside (a part thinner than the spacing).
// Angles: the paper proves every dihedral angle within [kStuffingMinDihedralDegrees,
// kStuffingMaxDihedralDegrees] for these thresholds. The order of the warp is this code's own
// (stuffing_warp.h); no mesh measured with it has left the bounds, but a search over the
// configurations it allows finds one (one inside vertex, two warped ones, a cut point on a long
// edge) slightly under the lower bound: the bound is the paper's, checked by the tests, not
// proven for this code (docs/choices.md). The offset never takes a tet outside them (it
// checks each move).
// `grading`: levels of coarsening inside, 0..kMaxStuffingGrading; 0 is the uniform lattice
// (the output is the same as without the argument). Graded tets away from the surface keep
// their lattice shapes (all vertices inside and unwarped); the surface's side is the uniform one.
// Errors: InvalidArgument naming the field and value: resolution, grading, an empty surface, an index
// out of range, a non-finite coordinate, a surface that is not closed (a ray crosses it an
// odd number of times), a null `out`; OutOfMemory. `*out` and `*report` are unchanged on
// error; `report` may be null.
Status tetrahedralizeByStuffing(const SurfaceMesh& surface, int resolution, TetMesh* out,
                                StuffingReport* report = nullptr,
                                StuffingBoundary boundary = StuffingBoundary::KeepVolume, int grading = 0);

}  // namespace vp
