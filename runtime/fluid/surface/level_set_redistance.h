// Redistancing of the liquid level set: makes phi a signed distance (|grad phi| = 1) in a
// narrow band around the surface again, keeping the zero isosurface where it was.
//
// 1. Surface cells (a 6-neighbour across the sign change) get d = phi / |grad phi|, the
//    subcell initialization of Russo and Smereka 2000 in its simple form: central differences
//    where phi is monotone along an axis (exact for a linear phi, so a plane does not move;
//    O((h/R)^2) relative on a sphere of radius R; a smooth rescaling phi * f keeps its zero
//    set to O(h^2)), the larger one-sided difference at an extremum along the axis (a thin
//    sheet), where the central one would vanish. |d| is capped at h, since the surface lies
//    within one cell of such a cell. These values stay fixed.
// 2. Band: breadth-first 6-neighbour layers from the surface cells, ceil(sqrt(3) W) + 1 of
//    them, which holds every cell within W h of the surface (a cell at distance d has a
//    6-neighbour path of at most sqrt(3) d / h + 1 steps to a surface cell).
// 3. Eikonal |grad d| = 1 on the band by the first-order Godunov upwind update (the one of
//    fast marching and fast sweeping, Zhao 2005: exact for planes), iterated as red-black
//    Gauss-Seidel from d = +inf until no value under the clamp W h drops by more than a
//    tolerance (an update reads only neighbours smaller than its result, so values at or
//    above the clamp never move one under it, and the result clamps them). Red cells read
//    only black neighbours, so each half-sweep is parallel and its result does not depend on
//    the worker count. A cell none of whose neighbours changed since its own last update is
//    skipped (the update would give its value again): later sweeps touch only the cells where
//    distances still move, with the same bits as full sweeps.
// 4. phi = sign(old phi) * min(d, W h) on the band, +-W h beyond it: a signed distance clamped
//    at W h (advection only reads phi within a few cells of the surface).
//
// Cost is linear in the band (about 2 sqrt(3) W cells per surface cell), not in the grid,
// except three cheap whole-grid passes (surface detection, listing the band in cell order so
// the sweeps walk memory in order, final write).
#pragma once

#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

struct RedistanceSettings {
  double bandCells = 4.0;         // W: exact distances up to W h, clamped beyond
  double tolerance = 1e-6;        // stop when no value under W h drops by more than tolerance * h
  int maxSweeps = 64;             // red-black sweep pairs
};

struct RedistanceStats {
  int64_t surfaceCells = 0, bandCells = 0;
  int sweeps = 0;
  bool converged = false;
};

struct RedistanceWorkspace {
  Array<double> distance;
  Array<uint8_t> layer;
  Array<uint8_t> stale;  // per band cell during the sweeps: a neighbour changed since its last update
  Array<int32_t> surface, band[2];  // band[0] red, band[1] black (i + j + k parity)
  Array<int32_t> reached;  // breadth-first queue: surface cells, then band cells as claimed
  std::vector<Array<int32_t>> chunkSurface;  // surface cells found per chunk of a slab
  std::vector<Array<int32_t>> chunkBand;     // band cells per chunk of a slab and colour
};

// phi: cellCount values in cell order, rewritten in place. Needs at least one sign change to
// do anything; without one phi is only clamped to +-W h. Runs RedistanceRun in one slice.
Status redistanceLevelSet(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const RedistanceSettings& settings,
                          RedistanceWorkspace& workspace, RedistanceStats* stats);

// redistanceLevelSet in slices, bitwise the same result however it is sliced and on any
// number of workers. A slice does at most samplesPerSlice samples of work (one at least) and
// runs on into the next pass when one ends, so slices cost about the same throughout:
// - surface detection (1), the band's lists (2) and the final write (4): cells, in slabs of
//   consecutive cells; a cell's result depends on phi alone, and the lists are appended in
//   cell order.
// - band layers (2): entries of the breadth-first queue, consecutive ones taken by the same
//   serial loop. The search is order-dependent (a cell joins the layer of whichever neighbour
//   reaches it first), so only the serial order keeps it.
// - the eikonal iteration (3): one colour's band entries in slabs. A red cell reads only
//   black ones and vice versa, so within a half-sweep no result depends on the order; the
//   half-sweep's largest drop is a max, exact in any order, kept across its slabs.
// prepare() checks the arguments and sizes the workspace but reads no values, so it may run
// before earlier work on phi. Between prepare() and the last slice, phi and the workspace
// belong to the run: nothing else may touch them.
class RedistanceRun {
 public:
  // cellWeights (null: none): the cells' open weights (solids/sliver_cells.h). A cell below
  // kSliverCellWeight is covered by a solid and holds the level set extended into it
  // (level_set_solid_extension.h), which is no surface: it seeds no distance, and a surface
  // cell beside it reads no crossing and no slope across it. Seeded from it, the liquid's
  // surface beside a solid at its waterline followed the extension's means every step and kept
  // a current of a few mm/s going there.
  Status prepare(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const RedistanceSettings& settings,
                 RedistanceWorkspace& workspace, int64_t samplesPerSlice, const double* cellWeights = nullptr);
  // Runs one slice; true once all is done (also after a failed or missing prepare()).
  bool advance();
  bool done() const { return pass_ == Pass::Done; }
  int64_t lastSliceSamples() const { return lastSliceSamples_; }
  const RedistanceStats& stats() const { return stats_; }  // once done

 private:
  enum class Pass : uint8_t { Surface, Band, List, Sweep, Write, Done };
  int64_t step(int64_t budget);  // part of the current pass; returns the samples it did
  void detectSurface(int64_t begin, int64_t end);
  int64_t claimBand(int64_t budget);
  void listBand(int64_t begin, int64_t end);
  double sweepSlab(int64_t begin, int64_t end);
  void finishSweep();
  void writeSlab(int64_t begin, int64_t end);

  TaskSystem* tasks_ = nullptr;
  MacGridSpec grid_;
  double* phi_ = nullptr;
  const double* cellWeights_ = nullptr;
  RedistanceSettings settings_;
  RedistanceWorkspace* ws_ = nullptr;
  int64_t samplesPerSlice_ = 1, cells_ = 0, lastSliceSamples_ = 0;
  int layers_ = 0;
  Pass pass_ = Pass::Done;
  int64_t position_ = 0;  // in the current pass (or half-sweep)
  int colour_ = 0;        // of the half-sweep running
  double drop_ = 0.0;     // largest drop of the sweep running
  RedistanceStats stats_;
};

}  // namespace vp
