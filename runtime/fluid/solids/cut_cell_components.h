// Cut cells that a collider splits: closes the faces of all but one piece of the cell.
//
// Why. A cell's open faces are exact (face_fraction_field.h), but the cell has one pressure
// and one smoke density. A collider thinner than the cell's projection onto its normal (a
// plate one cell thick slanted at 30 degrees: the cell spans 1.37 h across it) can cut a cell
// into two pieces on the two sides of the plate, each with its own open faces. The operator
// then couples the two sides through that cell, the projection sends fluid through the plate,
// and smoke follows; closing the smaller pieces alone stops it (tests/unit/fluid_smoke_test.cpp;
// figures in docs/choices.md, Fluids).
//
// What. For every cut cell (some face neither fully open nor fully closed) the collider union
// is sampled at the 8^3 nodes of a lattice that includes the cell's corners, edges and faces
// (spacing h/7), a node is open where every collider's signed distance is > 0, and the open
// nodes are joined into components through lattice edges (6-neighbours). A cell is split
// when two or more components reach its boundary; its main piece is the component with the
// most nodes. A face of a split cell stays open only where one of its boundary nodes lies in
// the main piece of the cell and, when the neighbour across the face is split too, in the
// neighbour's main piece; otherwise its open fraction is set to 0 (the piece behind it is
// treated as solid). Both cells see the same nodes on their common face, so the decision is
// the same from either side, and two open pieces on the two sides of a separator never share
// a node: after the pass, no chain of open faces crosses a collider that splits cells.
//
// Why not one pressure per piece (thin-shell cut cells, Azevedo et al. 2016). That needs
// several pressures, densities and velocities per cell, a multigrid and advection that know
// about them. Closing the smaller pieces keeps one unknown per cell and only changes face
// fractions, so the operator stays the same symmetric positive semidefinite finite-volume
// operator (multigrid and MIC(0) read it unchanged). The price: the closed piece's fluid is
// lost to the solid, so a separator much thinner than a cell acts about one cell thick.
//
// Which cells are sampled. Only cut cells (some face neither fully open nor fully closed)
// that a thin collider (a lower bound of its width below 2 h; meshes always), several
// colliders, or a domain side can split; a convex collider at least 2 h wide splits cells
// only near its edges, where its two sides join around the edge anyway. One convex collider
// leaves the cell in one piece when its open corners see each other through open space (the
// distance bound clears the segments between them), since every piece of a cube minus a
// convex solid holds a corner: those cells are not sampled either. So spheres, capsules and
// boxes a few cells across keep their exact fractions bit for bit.
//
// Limits. Separators thinner than the node spacing (h/7 along the worst axis) can fall
// between nodes and are not seen; an opening narrower than the spacing can be missed and its
// face closed in a split cell. A thick convex collider's edge pressed against another solid
// is handled (several colliders: sampled) but its edge pressed against the domain side only
// in the cells on that side.
//
// Cost: per sampled cell one signed-distance evaluation per node where the distance's
// Lipschitz bound does not settle a whole block of nodes at once (all 8^3 at worst) and a
// bit-parallel flood fill, far more than a cell's face fractions: hence sampling only the cells
// above (figures in docs/choices.md, Fluids). Static colliders pay it once; moving ones in the
// region they swept, every step.
#pragma once

#include <cstdint>

#include "collide/face_coverage.h"
#include "core/slab_passes.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

struct CutCellComponentStats {
  int64_t cutCells = 0;     // cells sampled
  int64_t splitCells = 0;   // cells with two or more open pieces
  int64_t closedFaces = 0;  // faces whose open fraction was set to 0
};

// Samples the cells in the cell index box around `box` (plus the margin that recomputeBox in
// face_fraction_field.cpp uses, so every cell touching a face it recomputed is included) and
// closes the faces of split cells' minor pieces. Idempotent: the decisions depend on the
// colliders only, so running it again, or over overlapping boxes, closes the same faces.
// `stats` may be null.
Status closeSplitCellPieces(TaskSystem& tasks, const PreparedCollider* const* colliders, int count, const Aabb& box,
                            FaceFractionField* field, CutCellComponentStats* stats);

// The same as passes of bounded slices (core/slab_passes.h): the cells' rows are sampled in
// parallel, then the faces are closed in one serial pass. The collider array, the colliders
// and the field must stay as they are, but for earlier passes, until these have run; `stats`
// (may be null) is filled by the last pass.
Status addSplitCellPasses(SlabPasses& passes, const PreparedCollider* const* colliders, int count, const Aabb& box,
                          FaceFractionField* field, CutCellComponentStats* stats);

}  // namespace vp
