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

#include <vector>

#include "core/status.h"
#include "core/task_system.h"
#include "fluid/face_fraction_field.h"

namespace vp {

constexpr double kDefaultHeavisideWidthCells = 1.5;

// H(phi) of the header for half-width `width` (metres).
double smoothedLiquidFraction(double phi, double width);

double liquidVolume(TaskSystem& tasks, const MacGridSpec& grid, const double* phi, const double* cellWeight,
                    double widthCells = kDefaultHeavisideWidthCells);

// Per cell: the mean of the open fractions of its six faces (colliders only; domain walls do
// not count), a first-order estimate of the cell's non-solid volume fraction: exact for an
// empty or a fully covered cell, and within a few tens of percent of a cut cell's fraction,
// which matters only in the thin shell of cells that colliders cut.
void cellOpenFractions(TaskSystem& tasks, const FaceFractionField& fractions, std::vector<double>* weights);

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
// within the limit).
Status correctLiquidVolume(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const double* cellWeight,
                           double targetVolume, const VolumeCorrectionSettings& settings,
                           VolumeCorrectionResult* result);

}  // namespace vp
