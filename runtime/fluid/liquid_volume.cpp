// Smoothed-Heaviside liquid volume and its correction (see liquid_volume.h).
#include "fluid/liquid_volume.h"

#include <cmath>

#include "core/parallel_for.h"

namespace vp {
namespace {

constexpr int64_t kCellGrain = 8192;

struct VolumeAndSlope {
  double volume = 0.0;  // sum of w H
  double slope = 0.0;   // sum of w dH/dphi (<= 0)
  VolumeAndSlope& operator+=(const VolumeAndSlope& o) {
    volume += o.volume;
    slope += o.slope;
    return *this;
  }
};

double fractionSlope(double phi, double width) {
  if (phi <= -width || phi >= width) return 0.0;
  return -0.5 * (1.0 + std::cos(M_PI * phi / width)) / width;
}

// The cells whose fraction can change under a shift of at most `reach`, packed: in chunk order,
// so sums over them do not depend on the worker count.
struct Band {
  std::vector<double> phi, weight;
  double fullWeight = 0.0;  // sum of w over cells that stay fully liquid
};

void gatherBand(TaskSystem& tasks, int64_t cells, const double* phi, const double* weight, double reach,
                Band* band) {
  const int64_t chunks = (cells + kCellGrain - 1) / kCellGrain;
  std::vector<Band> parts(static_cast<size_t>(chunks));
  parallelFor(tasks, chunks, 1, [&](int64_t first, int64_t last) {
    for (int64_t chunk = first; chunk < last; ++chunk) {
      Band& part = parts[static_cast<size_t>(chunk)];
      const int64_t end = std::min(cells, (chunk + 1) * kCellGrain);
      for (int64_t c = chunk * kCellGrain; c < end; ++c) {
        const double w = weight != nullptr ? weight[c] : 1.0;
        if (!(w > 0.0)) continue;
        if (phi[c] <= -reach) {
          part.fullWeight += w;
        } else if (phi[c] < reach) {
          part.phi.push_back(phi[c]);
          part.weight.push_back(w);
        }
      }
    }
  });
  band->phi.clear();
  band->weight.clear();
  band->fullWeight = 0.0;
  for (const Band& part : parts) {
    band->phi.insert(band->phi.end(), part.phi.begin(), part.phi.end());
    band->weight.insert(band->weight.end(), part.weight.begin(), part.weight.end());
    band->fullWeight += part.fullWeight;
  }
}

VolumeAndSlope evaluate(TaskSystem& tasks, const Band& band, double shift, double width) {
  VolumeAndSlope sum = parallelReduce<VolumeAndSlope>(
      tasks, static_cast<int64_t>(band.phi.size()), kCellGrain, [&](int64_t begin, int64_t end) {
        VolumeAndSlope part;
        for (int64_t b = begin; b < end; ++b) {
          const double p = band.phi[static_cast<size_t>(b)] + shift, w = band.weight[static_cast<size_t>(b)];
          part.volume += w * smoothedLiquidFraction(p, width);
          part.slope += w * fractionSlope(p, width);
        }
        return part;
      });
  sum.volume += band.fullWeight;
  return sum;
}

}  // namespace

double smoothedLiquidFraction(double phi, double width) {
  if (phi <= -width) return 1.0;
  if (phi >= width) return 0.0;
  return 0.5 * (1.0 - phi / width - std::sin(M_PI * phi / width) / M_PI);
}

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

void cellOpenFractions(TaskSystem& tasks, const FaceFractionField& fractions, std::vector<double>* weights) {
  const MacGridSpec& g = fractions.grid;
  const int64_t cells = static_cast<int64_t>(g.nx) * g.ny * g.nz;
  weights->resize(static_cast<size_t>(cells));
  parallelFor(tasks, cells, kCellGrain, [&](int64_t begin, int64_t end) {
    for (int64_t c = begin; c < end; ++c) {
      const int i = static_cast<int>(c % g.nx), j = static_cast<int>((c / g.nx) % g.ny),
                k = static_cast<int>(c / (static_cast<int64_t>(g.nx) * g.ny));
      double sum = 0.0;
      for (int a = 0; a < 3; ++a) {
        Eigen::Vector3i high(i, j, k);
        high[a] += 1;
        sum += fractions.open[a][fractions.faceIndex(a, i, j, k)] +
               fractions.open[a][fractions.faceIndex(a, high.x(), high.y(), high.z())];
      }
      (*weights)[static_cast<size_t>(c)] = sum / 6.0;
    }
  });
}

Status correctLiquidVolume(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const double* cellWeight,
                           double targetVolume, const VolumeCorrectionSettings& settings,
                           VolumeCorrectionResult* result) {
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
  const double h = grid.h, cellVolume = h * h * h;
  const double width = settings.widthCells * h, maxShift = settings.maxShiftCells * h;
  const int64_t cells = static_cast<int64_t>(grid.nx) * grid.ny * grid.nz;
  Band band;
  gatherBand(tasks, cells, phi, cellWeight, width + maxShift, &band);
  const double target = targetVolume / cellVolume;  // in cells
  // V(shift) decreases with the shift; keep a bracket [low, high] around the root.
  double low = -maxShift, high = maxShift, shift = 0.0;
  VolumeAndSlope at = evaluate(tasks, band, shift, width);
  VolumeCorrectionResult out;
  out.volumeBefore = at.volume * cellVolume;
  for (; out.iterations < settings.maxIterations; ++out.iterations) {
    const double excess = at.volume - target;
    if (std::fabs(excess) <= settings.relativeTolerance * target) {
      out.converged = true;
      break;
    }
    if (excess > 0.0) low = shift;  // too much liquid: the root is at a larger shift
    else high = shift;
    double next = at.slope < 0.0 ? shift - excess / at.slope : 0.5 * (low + high);
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (high - low <= 1e-15 * h) break;  // the root is beyond the limit, or no surface moves
    shift = next;
    at = evaluate(tasks, band, shift, width);
  }
  out.volumeAfter = at.volume * cellVolume;
  out.shift = shift;
  if (shift != 0.0)
    parallelFor(tasks, cells, kCellGrain, [&](int64_t begin, int64_t end) {
      for (int64_t c = begin; c < end; ++c) phi[c] += shift;
    });
  if (result != nullptr) *result = out;
  return Status::Ok;
}

}  // namespace vp
