// Liquid volume of a level set and its correction by a uniform shift of phi.
//
// Volume = h^3 sum_c w_c H(phi_c), with H the smoothed Heaviside of the liquid (Sussman,
// Smereka, Osher 1994; Osher and Fedkiw's book): 1 for phi <= -e, 0 for phi >= e, and
// H = (1 - phi/e - sin(pi phi/e)/pi) / 2 in between, e = widthCells * h. Why the smoothed
// Heaviside rather than sub-sampling cells: it is one evaluation per cell (sub-sampling needs
// tens of trilinear samples per surface cell every step), and it is smooth in a shift of phi,
// so the correction's Newton iteration converges quadratically. Its bias is a curvature term:
// for a sphere of radius R the sum exceeds 4/3 pi R^3 by about 0.39 (e/R)^2 relative (the
// smoothing is odd about the surface but the area grows outwards), e.g. 0.4 % at R = 16 h with
// e = 1.5 h; marching cubes on the same phi loses a similar amount the other way (chords cut
// inside), so the two agree to about 1 %. The correction only needs the measure to be the same
// function of phi at all times, which it is.
//
// w_c: an optional per-cell weight in [0, 1] (nullptr = 1) for the part of a cell not inside
// colliders; cellOpenFractions() gives one from the face fractions. Solid cells (weight 0)
// may carry any phi.
//
// Correction: find c with V(phi + c) = target (c > 0 shrinks the liquid) by safeguarded Newton
// (bisection when a step leaves the bracket), then add c to every cell. A uniform shift moves
// the whole surface along its normal by -c; for the small per-step drift of a level set this
// is the usual global fix (it spreads the lost volume evenly over the surface). The shift is limited to maxShiftCells * h per call so a large mismatch
// (an emitter switched on) is caught up over several steps rather than in one jump.
#pragma once

#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/slab_passes.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/solids/face_fraction_field.h"
#include "gpu_kernels/level_set_kernels.h"

namespace vp {

constexpr double kDefaultHeavisideWidthCells = 1.5;

// H(phi) of the header for half-width `width` (metres), a kernel body.
using kernels::smoothedLiquidFraction;

double liquidVolume(TaskSystem& tasks, const MacGridSpec& grid, const double* phi, const double* cellWeight,
                    double widthCells = kDefaultHeavisideWidthCells);

// Per cell: the mean of the open fractions of its six faces (colliders only; domain walls do
// not count), a first-order estimate of the cell's non-solid volume fraction: exact for an
// empty or a fully covered cell, and within a few tens of percent of a cut cell's fraction,
// which matters only in the thin shell of cells that colliders cut.
void cellOpenFractions(TaskSystem& tasks, const FaceFractionField& fractions, Array<double>* weights);
// The same as a pass of bounded slices (core/slab_passes.h); sizes `weights` now.
void addCellOpenFractionPasses(SlabPasses& passes, const FaceFractionField& fractions, Array<double>* weights);

struct VolumeCorrectionSettings {
  double widthCells = kDefaultHeavisideWidthCells;
  double relativeTolerance = 1e-9;  // on |V - target| / target
  int maxIterations = 20;
  double maxShiftCells = 1.0;
};

struct VolumeCorrectionResult {
  double shift = 0.0;  // added to phi (metres)
  double volumeBefore = 0.0, volumeAfter = 0.0;
  int iterations = 0;
  bool converged = false;  // false: the shift hit maxShiftCells, or no surface to move
};

// targetVolume > 0 (m^3). phi is shifted in place (also when not converged: by the best shift
// within the limit). Runs VolumeCorrectionRun in one slice.
Status correctLiquidVolume(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const double* cellWeight,
                           double targetVolume, const VolumeCorrectionSettings& settings,
                           VolumeCorrectionResult* result);

// correctLiquidVolume in slices, bitwise the same result however it is sliced and on any
// number of workers. A slice does at most samplesPerSlice samples of work (one at least) and
// runs on into the next pass when one ends, so slices cost about the same throughout:
// - gathering the band (the cells that a shift within the limit can change): cells in slabs;
// - each evaluation of V and its slope at a trial shift (one per iteration): band entries in
//   slabs. A cell's term depends on its own phi only, but the sums must be parallelReduce's
//   (fixed chunks, added in chunk order): a slab adds the chunks it completes to the sum in
//   order and passes the partial of a chunk it leaves unfinished on to the next slab;
// - the shift of phi: cells in slabs.
// The Newton/bisection update between evaluations is a few operations, done by the slice that
// ends an evaluation. phi is read while the band is gathered and written by the last pass.
// prepare() checks the arguments but reads no values, so it may run before earlier work on
// phi. Between prepare() and the last slice, phi and cellWeight belong to the run: nothing
// else may touch them. A run kept from step to step reuses its storage.
class VolumeCorrectionRun {
 public:
  Status prepare(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const double* cellWeight,
                 double targetVolume, const VolumeCorrectionSettings& settings, int64_t samplesPerSlice);
  // Runs one slice; true once all is done (also after a failed or missing prepare()).
  bool advance();
  bool done() const { return pass_ == Pass::Done; }
  int64_t lastSliceSamples() const { return lastSliceSamples_; }
  const VolumeCorrectionResult& result() const { return result_; }  // once done

 private:
  enum class Pass : uint8_t { Gather, Evaluate, Shift, Done };
  // The cells whose fraction can change under the shifts allowed, in cell order.
  struct Band {
    Array<double> phi, weight;
    double fullWeight = 0.0;  // sum of w over cells that stay fully liquid
    Band& operator+=(const Band& o);
  };
  struct VolumeAndSlope {
    double volume = 0.0;  // sum of w H
    double slope = 0.0;   // sum of w dH/dphi (<= 0)
    VolumeAndSlope& operator+=(const VolumeAndSlope& o);
  };
  // A sum over chunks added a slab at a time: `open` holds the partial of the chunk a slab
  // left unfinished.
  template <class T>
  struct ChunkedSum {
    T total, open;
    Array<T> pieces;  // scratch: per chunk of a slab
  };

  int64_t step(int64_t budget);  // part of the current pass; returns the samples it did
  void startEvaluation();
  void evaluated();
  bool nextShift();  // false when the iteration ends

  TaskSystem* tasks_ = nullptr;
  MacGridSpec grid_;
  double* phi_ = nullptr;
  const double* weight_ = nullptr;
  VolumeCorrectionSettings settings_;
  double target_ = 0.0;  // in cells
  int64_t samplesPerSlice_ = 1, cells_ = 0, lastSliceSamples_ = 0;
  Pass pass_ = Pass::Done;
  int64_t position_ = 0;  // in the current pass
  double low_ = 0.0, high_ = 0.0, shift_ = 0.0;  // V(shift) decreases: the root is in [low, high]
  VolumeAndSlope at_;  // at shift_
  bool measured_ = false;  // volumeBefore is known
  ChunkedSum<Band> band_;
  ChunkedSum<VolumeAndSlope> sums_;
  VolumeCorrectionResult result_;
};

}  // namespace vp
