// The liquid level set inside solids: what a cell holds while a collider covers it is what it
// will hold when the collider moves on, so it must describe the liquid around the solid.
// Advection alone leaves whatever the solid's own motion dragged in (a floating body drags
// air under the surface, and the cells it uncovers then read as a bubble under it: the
// pressure there drops to zero and the body loses its buoyancy).
//
// Covered cells (open weight below kMaxCoveredCellWeight, see cellOpenFractions) take, layer
// by layer from the fluid side, the mean phi of their already-known face neighbours: liquid
// below a floating body's waterline, air above it. Redistancing afterwards turns the values
// into distances again.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "fluid/solids/face_fraction_field.h"
#include "fluid/solids/sliver_cells.h"

namespace vp {

// Covered cells are those below the sliver weight, which the fractions close anyway
// (sliver_cells.h). A cell open through one whole face is above it and keeps the phi that
// advection gives it, or its surface cannot rise with what flows in: extending such a cell
// ties its surface to its neighbours', and the projection then drains the inflow up the cut
// column through a surface that never moves, as a jet up the collider's wall far faster than
// the flow (fluid_liquid_cut_wall_test.cpp).
constexpr double kMaxCoveredCellWeight = kSliverCellWeight;

// cellWeights and phi: cellCount values in cell order; scratch is the run's list of unknown
// cells. Does nothing when the sizes do not match the grid. Runs SolidExtensionRun in one
// slice.
void extendLevelSetIntoSolids(const MacGridSpec& grid, const Array<double>& cellWeights, Array<double>& phi,
                              Array<int64_t>& scratch);

// extendLevelSetIntoSolids in slices, bitwise the same result however it is sliced. Serial. A
// slice does at most samplesPerSlice samples of work (one at least) and runs on into the next
// pass when one ends:
// - listing the covered cells: cells in slabs of consecutive cells, appended in order;
// - each layer's scan of the unknown cells: entries in slabs. The scan only reads (values are
//   written after it), so no result depends on the order; the lists of cells found and still
//   unknown keep the serial order;
// - writing the layer's values: entries in slabs, each writing its own cell.
// prepare() checks the sizes but reads no values, so it may run before earlier work on phi.
// Between prepare() and the last slice, phi and scratch belong to the run and cellWeights
// must stay as they are. A run kept from step to step reuses its storage.
class SolidExtensionRun {
 public:
  Status prepare(const MacGridSpec& grid, const Array<double>& cellWeights, Array<double>& phi,
                 Array<int64_t>& scratch, int64_t samplesPerSlice);
  // Runs one slice; true once all is done (also after a failed or missing prepare()).
  bool advance();
  bool done() const { return pass_ == Pass::Done; }
  int64_t lastSliceSamples() const { return lastSliceSamples_; }

 private:
  enum class Pass : uint8_t { Collect, Scan, Write, Done };
  int64_t step(int64_t budget);  // part of the current pass; returns the samples it did

  MacGridSpec grid_;
  const Array<double>* weights_ = nullptr;
  Array<double>* phi_ = nullptr;
  Array<int64_t>* unknown_ = nullptr;
  int64_t samplesPerSlice_ = 1, lastSliceSamples_ = 0;
  Pass pass_ = Pass::Done;
  int64_t position_ = 0;  // in the current pass
  Array<int8_t> pending_;  // per cell: 1 while unknown
  Array<int64_t> still_;   // unknown after this layer
  Array<std::pair<int64_t, double>> found_;  // this layer's cells and values
};

}  // namespace vp
