// Smoothed-Heaviside liquid volume and its correction (see liquid_volume.h).
#include "fluid/surface/liquid_volume.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/parallel_for.h"
#include "core/slab_passes.h"
#include "fluid/cell_lattice.h"
#include "gpu_kernels/mac_layout.h"

namespace vp {
namespace {

constexpr int64_t kCellGrain = 8192;

// Adds the slab [begin, end) of a sum over [0, n) that parallelReduce would cut into chunks
// of kCellGrain: accumulate(b, e, acc) adds [b, e) onto acc in index order. The chunks the slab
// completes go to sum.total in chunk order; one it leaves unfinished waits in sum.open, so
// every chunk's partial is built up in order from zero, however the slabs cut it.
template <class Sum, class Accumulate>
void addSlab(TaskSystem& tasks, int64_t n, int64_t begin, int64_t end, const Accumulate& accumulate, Sum& sum) {
  if (begin >= end) return;
  const int64_t firstChunk = begin / kCellGrain, pieces = (end - 1) / kCellGrain - firstChunk + 1;
  sum.pieces.resize(static_cast<size_t>(pieces));
  sum.pieces[0] = std::move(sum.open);
  for (int64_t p = 1; p < pieces; ++p) sum.pieces[static_cast<size_t>(p)] = {};
  parallelFor(tasks, pieces, 1, [&](int64_t first, int64_t last) {
    for (int64_t p = first; p < last; ++p) {
      const int64_t chunk = firstChunk + p;
      accumulate(std::max(begin, chunk * kCellGrain), std::min(end, (chunk + 1) * kCellGrain),
                 sum.pieces[static_cast<size_t>(p)]);
    }
  });
  sum.open = {};
  for (int64_t p = 0; p < pieces; ++p) {
    if (std::min(end, (firstChunk + p + 1) * kCellGrain) == std::min(n, (firstChunk + p + 1) * kCellGrain))
      sum.total += sum.pieces[static_cast<size_t>(p)];
    else
      sum.open = std::move(sum.pieces[static_cast<size_t>(p)]);
  }
}

}  // namespace

double liquidVolume(TaskSystem& tasks, const MacGridSpec& grid, const double* phi, const double* cellWeight,
                    double widthCells) {
  const double width = widthCells * grid.h;
  const int64_t cells = static_cast<int64_t>(grid.nx) * grid.ny * grid.nz;
  const double sum = parallelReduce<double>(tasks, cells, kCellGrain, [&](int64_t begin, int64_t end) {
    double part = 0.0;
    for (int64_t c = begin; c < end; ++c)
      part += (cellWeight != nullptr ? cellWeight[c] : 1.0) * smoothedLiquidFraction(phi[c], width);
    return part;
  });
  return sum * grid.h * grid.h * grid.h;
}

namespace {

void cellOpenFractionRange(const FaceFractionField& fractions, int64_t begin, int64_t end, double* weights) {
  const MacGridSpec& g = fractions.grid;
  const kernels::MacLayout layout{g.nx, g.ny, g.nz, {}};  // face indices only: no wall flags read
  forCellsInRange(g, begin, end, [&](int64_t c, int i, int j, int k) {
    double sum = 0.0;
    for (int a = 0; a < 3; ++a) {
      const int64_t low = layout.faceIndex(a, i, j, k);
      const int64_t high = layout.faceIndex(a, i + (a == 0), j + (a == 1), k + (a == 2));
      sum += fractions.open[a][static_cast<size_t>(low)] + fractions.open[a][static_cast<size_t>(high)];
    }
    weights[c] = sum / 6.0;
  });
}

int64_t cellCount(const MacGridSpec& g) { return static_cast<int64_t>(g.nx) * g.ny * g.nz; }

}  // namespace

void cellOpenFractions(TaskSystem& tasks, const FaceFractionField& fractions, Array<double>* weights) {
  const int64_t cells = cellCount(fractions.grid);
  weights->resize(static_cast<size_t>(cells));
  parallelFor(tasks, cells, kCellGrain, [&](int64_t begin, int64_t end) {
    cellOpenFractionRange(fractions, begin, end, weights->data());
  });
}

void addCellOpenFractionPasses(SlabPasses& passes, const FaceFractionField& fractions, Array<double>* weights) {
  const int64_t cells = cellCount(fractions.grid);
  weights->resize(static_cast<size_t>(cells));
  passes.addParallel(cells, 1, kCellGrain, [&fractions, w = weights->data()](int64_t begin, int64_t end) {
    cellOpenFractionRange(fractions, begin, end, w);
  });
}

Status correctLiquidVolume(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const double* cellWeight,
                           double targetVolume, const VolumeCorrectionSettings& settings,
                           VolumeCorrectionResult* result) {
  VolumeCorrectionRun run;
  VP_TRY(run.prepare(tasks, grid, phi, cellWeight, targetVolume, settings, std::numeric_limits<int64_t>::max()));
  while (!run.advance()) {
  }
  if (result != nullptr) *result = run.result();
  return Status::Ok;
}

VolumeCorrectionRun::Band& VolumeCorrectionRun::Band::operator+=(const Band& o) {
  phi.insert(phi.end(), o.phi.begin(), o.phi.end());
  weight.insert(weight.end(), o.weight.begin(), o.weight.end());
  fullWeight += o.fullWeight;
  return *this;
}

VolumeCorrectionRun::VolumeAndSlope& VolumeCorrectionRun::VolumeAndSlope::operator+=(const VolumeAndSlope& o) {
  volume += o.volume;
  slope += o.slope;
  return *this;
}

Status VolumeCorrectionRun::prepare(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const double* cellWeight,
                                    double targetVolume, const VolumeCorrectionSettings& settings,
                                    int64_t samplesPerSlice) {
  pass_ = Pass::Done;
  if (phi == nullptr) return fail(Status::InvalidArgument, "volume correction: phi is null");
  if (!(targetVolume > 0.0) || !std::isfinite(targetVolume))
    return fail(Status::InvalidArgument, "volume correction: targetVolume = %g must be positive and finite",
                targetVolume);
  if (!(settings.widthCells > 0.0) || !(settings.maxShiftCells > 0.0) || !(settings.relativeTolerance > 0.0) ||
      settings.maxIterations < 1)
    return fail(Status::InvalidArgument,
                "volume correction: widthCells = %g, maxShiftCells = %g, relativeTolerance = %g must be positive "
                "and maxIterations = %d at least 1",
                settings.widthCells, settings.maxShiftCells, settings.relativeTolerance, settings.maxIterations);
  if (samplesPerSlice < 1)
    return fail(Status::InvalidArgument, "volume correction: samplesPerSlice = %lld must be >= 1",
                static_cast<long long>(samplesPerSlice));
  tasks_ = &tasks;
  grid_ = grid;
  phi_ = phi;
  weight_ = cellWeight;
  settings_ = settings;
  const double h = grid.h;
  target_ = targetVolume / (h * h * h);
  samplesPerSlice_ = samplesPerSlice;
  cells_ = static_cast<int64_t>(grid.nx) * grid.ny * grid.nz;
  lastSliceSamples_ = 0;
  pass_ = Pass::Gather;
  position_ = 0;
  low_ = -settings.maxShiftCells * h;
  high_ = settings.maxShiftCells * h;
  shift_ = 0.0;
  measured_ = false;
  for (Band* b : {&band_.total, &band_.open}) {
    b->phi.clear();
    b->weight.clear();
    b->fullWeight = 0.0;
  }
  result_ = VolumeCorrectionResult{};
  return Status::Ok;
}

bool VolumeCorrectionRun::advance() {
  lastSliceSamples_ = runSamplesUpTo(
      samplesPerSlice_, [this] { return pass_ == Pass::Done; }, [this](int64_t left) { return step(left); });
  return pass_ == Pass::Done;
}

int64_t VolumeCorrectionRun::step(int64_t budget) {
  const double h = grid_.h, width = settings_.widthCells * h;
  const int64_t passLength = pass_ == Pass::Evaluate ? static_cast<int64_t>(band_.total.phi.size()) : cells_;
  const int64_t begin = position_, end = begin + std::min(budget, passLength - begin);
  position_ = end;
  switch (pass_) {
    case Pass::Gather: {
      const double reach = width + settings_.maxShiftCells * h;
      addSlab(*tasks_, cells_, begin, end, [&](int64_t first, int64_t last, Band& part) {
        for (int64_t c = first; c < last; ++c) {
          const double w = weight_ != nullptr ? weight_[c] : 1.0;
          if (!(w > 0.0)) continue;
          if (phi_[c] <= -reach) {
            part.fullWeight += w;
          } else if (phi_[c] < reach) {
            part.phi.push_back(phi_[c]);
            part.weight.push_back(w);
          }
        }
      }, band_);
      if (end == cells_) startEvaluation();
      break;
    }
    case Pass::Evaluate: {
      const Band& band = band_.total;
      addSlab(*tasks_, passLength, begin, end, [&](int64_t first, int64_t last, VolumeAndSlope& part) {
        for (int64_t b = first; b < last; ++b) {
          const double p = band.phi[static_cast<size_t>(b)] + shift_, w = band.weight[static_cast<size_t>(b)];
          part.volume += w * smoothedLiquidFraction(p, width);
          part.slope += w * kernels::liquidFractionSlope(p, width);
        }
      }, sums_);
      if (end == passLength) evaluated();
      break;
    }
    case Pass::Shift: {
      const double shift = shift_;
      double* phi = phi_;
      parallelFor(*tasks_, end - begin, kCellGrain, [&](int64_t first, int64_t last) {
        for (int64_t c = begin + first; c < begin + last; ++c) phi[c] += shift;
      });
      if (end == cells_) pass_ = Pass::Done;
      break;
    }
    case Pass::Done:
      break;
  }
  return end - begin;
}

void VolumeCorrectionRun::startEvaluation() {
  pass_ = Pass::Evaluate;
  position_ = 0;
  sums_.total = {};
  sums_.open = {};
}

// An evaluation is complete: record it, then the next trial shift or the end.
void VolumeCorrectionRun::evaluated() {
  const double cellVolume = grid_.h * grid_.h * grid_.h;
  at_ = sums_.total;
  at_.volume += band_.total.fullWeight;
  if (measured_) ++result_.iterations;
  else result_.volumeBefore = at_.volume * cellVolume;
  measured_ = true;
  if (nextShift()) {
    startEvaluation();
    return;
  }
  result_.volumeAfter = at_.volume * cellVolume;
  result_.shift = shift_;
  pass_ = shift_ != 0.0 ? Pass::Shift : Pass::Done;
  position_ = 0;
}

// Safeguarded Newton: bisection when a step leaves the bracket.
bool VolumeCorrectionRun::nextShift() {
  if (result_.iterations >= settings_.maxIterations) return false;
  const double excess = at_.volume - target_;
  if (std::fabs(excess) <= settings_.relativeTolerance * target_) {
    result_.converged = true;
    return false;
  }
  if (excess > 0.0) low_ = shift_;  // too much liquid: the root is at a larger shift
  else high_ = shift_;
  double next = at_.slope < 0.0 ? shift_ - excess / at_.slope : 0.5 * (low_ + high_);
  if (!(next > low_ && next < high_)) next = 0.5 * (low_ + high_);
  if (high_ - low_ <= 1e-15 * grid_.h) return false;  // the root is beyond the limit, or no surface moves
  shift_ = next;
  return true;
}

}  // namespace vp
