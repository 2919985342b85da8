// Layered velocity extrapolation (see velocity_extrapolation.h).
#include "fluid/surface/velocity_extrapolation.h"

#include <algorithm>
#include <limits>

#include "core/parallel_for.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/surface/free_surface.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 16;  // face rows (one row = dimX faces) per parallel chunk
constexpr int kMaxLayers = 250;    // marks are bytes; 253 to 255 are reserved
// A face the running layer has claimed, until its value is set (above every layer, so it is
// no source, and not kExtrapolationUnreached, so it is claimed once).
constexpr uint8_t kClaimed = 253;
static_assert(kMaxLayers < kClaimed && kClaimed < kExtrapolationFixed, "marks: layers, claimed, fixed, unreached");

// visit(neighbour) for the same-axis neighbours of face f = (i, j, k) inside its lattice, in
// the order the layers average them (-x, +x, -y, +y, -z, +z).
template <class Visit>
void forFaceNeighbours(const Eigen::Vector3i& d, int64_t f, int64_t i, int64_t j, int64_t k, const Visit& visit) {
  const int64_t sy = d.x(), sz = static_cast<int64_t>(d.x()) * d.y();
  if (i > 0) visit(f - 1);
  if (i + 1 < d.x()) visit(f + 1);
  if (j > 0) visit(f - sy);
  if (j + 1 < d.y()) visit(f + sy);
  if (k > 0) visit(f - sz);
  if (k + 1 < d.z()) visit(f + sz);
}
template <class Visit>
void forFaceNeighbours(const Eigen::Vector3i& d, int64_t f, const Visit& visit) {
  const int64_t sy = d.x(), sz = static_cast<int64_t>(d.x()) * d.y();
  forFaceNeighbours(d, f, f % sy, (f / sy) % d.y(), f / sz, visit);
}

// The mean of f's neighbours with marks below `layer` (n: how many there are).
template <class Neighbours>
double meanOfSources(const uint8_t* mark, const double* u, int layer, const Neighbours& neighbours, int* n) {
  double sum = 0.0;
  *n = 0;
  neighbours([&](int64_t nb) {
    if (mark[nb] < layer) {
      sum += u[nb];
      ++*n;
    }
  });
  return *n > 0 ? sum / *n : 0.0;
}

}  // namespace

Status extrapolateVelocity(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions,
                           const double* liquidPhi, const VelocityExtrapolationSettings& settings,
                           VelocityExtrapolationState& state) {
  VelocityExtrapolationRun run;
  VP_TRY(run.prepare(tasks, grid, fractions, liquidPhi, settings, state, std::numeric_limits<int64_t>::max()));
  while (!run.advance()) {
  }
  return Status::Ok;
}

Status VelocityExtrapolationRun::prepare(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions,
                                         const double* liquidPhi, const VelocityExtrapolationSettings& settings,
                                         VelocityExtrapolationState& state, int64_t samplesPerSlice) {
  pass_ = Pass::Done;
  if (liquidPhi == nullptr) return fail(Status::InvalidArgument, "velocity extrapolation: liquidPhi is null");
  if (settings.layers < 0 || settings.layers > kMaxLayers)
    return fail(Status::InvalidArgument, "velocity extrapolation: layers = %d must be in [0, %d]", settings.layers,
                kMaxLayers);
  if (!sameGrid(grid.spec, fractions.grid))
    return fail(Status::InvalidArgument, "velocity extrapolation: face fractions belong to another grid");
  if (samplesPerSlice < 1)
    return fail(Status::InvalidArgument, "velocity extrapolation: samplesPerSlice = %lld must be >= 1",
                static_cast<long long>(samplesPerSlice));
  tasks_ = &tasks;
  grid_ = &grid;
  fractions_ = &fractions;
  liquidPhi_ = liquidPhi;
  settings_ = settings;
  state_ = &state;
  samplesPerSlice_ = samplesPerSlice;
  lastSliceSamples_ = 0;
  for (int a = 0; a < 3; ++a) {
    state.mark[a].resize(grid.velocity[a].size());
    lastLayer_[a].clear();
  }
  claimedAxis_ = false;
  pass_ = Pass::Mark;
  axis_ = 0;
  layer_ = 0;
  row_ = 0;
  layerFaces_ = 0;
  return Status::Ok;
}

// Slabs of whole face rows (of claimed faces for layers after the first): as many as the
// slice has room for, one when it has done nothing.
bool VelocityExtrapolationRun::advance() {
  lastSliceSamples_ = 0;
  while (pass_ != Pass::Done) {
    if (pass_ == Pass::Layer && layer_ > 1) {
      if (!claimedAxis_) {  // first the claim, in slabs of the last layer's entries
        const int64_t length = static_cast<int64_t>(lastLayer_[axis_].size());
        if (row_ == 0) claimed_.clear();
        int64_t take = std::min(length - row_, std::max<int64_t>(samplesPerSlice_ - lastSliceSamples_, 0));
        if (take == 0 && length > row_) {
          if (lastSliceSamples_ > 0) break;
          take = 1;
        }
        claimFrontier(row_, row_ + take);
        row_ += take;
        lastSliceSamples_ += take;
        if (row_ < length) continue;
        claimedAxis_ = true;
        row_ = 0;
      }
      const int64_t length = static_cast<int64_t>(claimed_.size());
      int64_t take = std::min(length - row_, std::max<int64_t>(samplesPerSlice_ - lastSliceSamples_, 0));
      if (take == 0 && length > row_) {
        if (lastSliceSamples_ > 0) break;
        take = 1;
      }
      const int64_t begin = row_;
      row_ += take;
      lastSliceSamples_ += take;
      if (take > 0) extrapolateFrontier(begin, row_);
      if (row_ == length) {
        finishFrontier();
        nextAxis();
      }
      continue;
    }
    const Eigen::Vector3i d = grid_->faceDims(axis_);
    const int64_t rows = static_cast<int64_t>(d.z()) * d.y();
    int64_t take = std::min(rows - row_, std::max<int64_t>(samplesPerSlice_ - lastSliceSamples_, 0) / d.x());
    if (take == 0) {
      if (lastSliceSamples_ > 0) break;
      take = 1;
    }
    const int64_t begin = row_;
    row_ += take;
    lastSliceSamples_ += take * d.x();
    switch (pass_) {
      case Pass::Mark: markRows(begin, row_); break;
      case Pass::Layer: extrapolateRows(begin, row_); break;
      case Pass::Zero: zeroRows(begin, row_); break;
      case Pass::Done: break;
    }
    if (row_ == rows) nextAxis();
  }
  return pass_ == Pass::Done;
}

// The pass after one axis is done: the next axis, the next layer (none when the last one set
// nothing or was the last), the zeroing, the end.
void VelocityExtrapolationRun::nextAxis() {
  row_ = 0;
  if (++axis_ < 3) return;
  axis_ = 0;
  const bool moreLayers = pass_ == Pass::Mark    ? settings_.layers > 0
                          : pass_ == Pass::Layer ? layerFaces_ > 0 && layer_ < settings_.layers
                                                 : false;
  if (moreLayers) {
    pass_ = Pass::Layer;
    ++layer_;
    layerFaces_ = 0;
  } else {
    pass_ = pass_ != Pass::Zero && settings_.zeroUnreached ? Pass::Zero : Pass::Done;
  }
}

// The two cells' indices follow from the row and i, so they are set up once per row.
void VelocityExtrapolationRun::markRows(int64_t begin, int64_t end) {
  const MacGrid& grid = *grid_;
  const MacGridSpec& g = grid.spec;
  const int a = axis_;
  const Eigen::Vector3i d = grid.faceDims(a);
  const int cellsAlong = g.nx * (a == 0) + g.ny * (a == 1) + g.nz * (a == 2);
  const int64_t cellStride = a == 0 ? 1 : a == 1 ? g.nx : static_cast<int64_t>(g.nx) * g.ny;
  const double* phi = liquidPhi_;
  const double* open = fractions_->open[a].data();
  const double minSource = settings_.minSourceOpenFraction;
  const bool intoClosed = settings_.intoClosedFaces;
  uint8_t* mark = state_->mark[a].data();
  // Known (0) when open enough and next to the liquid; else a target when open (or closed and
  // intoClosedFaces); else fixed.
  auto initialMark = [minSource, intoClosed](double fraction, bool liquid) -> uint8_t {
    const bool isOpen = fraction > 0.0;
    if (isOpen && liquid && fraction >= minSource) return 0;
    return isOpen || intoClosed ? kExtrapolationUnreached : kExtrapolationFixed;
  };
  parallelFor(*tasks_, end - begin, kRowGrain, [&](int64_t first, int64_t last) {
    for (int64_t row = begin + first; row < begin + last; ++row) {
      const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
      const int64_t f0 = d.x() * row;
      // The index of cell (i, j, k), the face's high side (read only when it is inside the grid).
      const int64_t cellRow = static_cast<int64_t>(g.nx) * (j + static_cast<int64_t>(g.ny) * k);
      // A face on a domain side may be a Wall face and has a cell on one side only.
      auto sideFace = [&](int i) {
        const int along = a == 0 ? i : a == 1 ? j : k;
        if (grid.isWallFace(a, i, j, k)) {
          mark[f0 + i] = kExtrapolationFixed;
          return;
        }
        const int64_t high = cellRow + i;
        const bool liquid =
            (along > 0 && isLiquid(phi[high - cellStride])) || (along < cellsAlong && isLiquid(phi[high]));
        mark[f0 + i] = initialMark(effectiveOpenFraction(grid, *fractions_, a, i, j, k), liquid);
      };
      const int rowAlong = a == 1 ? j : k;
      if (a != 0 && (rowAlong == 0 || rowAlong == cellsAlong)) {
        for (int i = 0; i < d.x(); ++i) sideFace(i);
        continue;
      }
      // Interior faces: both cells exist and no face is a Wall face.
      const int iBegin = a == 0 ? 1 : 0, iEnd = a == 0 ? d.x() - 1 : d.x();
      for (int i = iBegin; i < iEnd; ++i) {
        const int64_t high = cellRow + i;
        const bool liquid = isLiquid(phi[high - cellStride]) || isLiquid(phi[high]);
        mark[f0 + i] = initialMark(openedFraction(open[f0 + i]), liquid);
      }
      if (a == 0) {
        sideFace(0);
        sideFace(d.x() - 1);
      }
    }
  });
}

// One layer on rows [begin, end) of an axis: a parallel scan writes the new faces' velocities
// (they are unreached, so no other face of this layer reads them) and lists them per chunk;
// their marks are set after the scan, so every face of the layer saw the marks of the earlier
// layers only.
void VelocityExtrapolationRun::extrapolateRows(int64_t begin, int64_t end) {
  const int layer = layer_;
  const Eigen::Vector3i d = grid_->faceDims(axis_);
  uint8_t* mark = state_->mark[axis_].data();
  double* u = grid_->velocity[axis_].data();
  const int64_t sy = d.x();
  const int64_t chunks = (end - begin + kRowGrain - 1) / kRowGrain;
  if (static_cast<int64_t>(assigned_.size()) < chunks) assigned_.resize(static_cast<size_t>(chunks));
  parallelFor(*tasks_, chunks, 1, [&](int64_t firstChunk, int64_t lastChunk) {
    for (int64_t chunk = firstChunk; chunk < lastChunk; ++chunk) {
      Array<int64_t>& out = assigned_[static_cast<size_t>(chunk)];
      out.clear();
      for (int64_t row = begin + chunk * kRowGrain; row < std::min(end, begin + (chunk + 1) * kRowGrain); ++row) {
        const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
        const int64_t first = row * sy;
        for (int i = 0; i < d.x(); ++i) {
          const int64_t f = first + i;
          if (mark[f] != kExtrapolationUnreached) continue;
          int n;
          const double mean = meanOfSources(mark, u, layer, [&](const auto& visit) {
            forFaceNeighbours(d, f, i, j, k, visit);
          }, &n);
          if (n == 0) continue;
          u[f] = mean;
          out.push_back(f);
        }
      }
    }
  });
  for (int64_t chunk = 0; chunk < chunks; ++chunk) {
    const Array<int64_t>& set = assigned_[static_cast<size_t>(chunk)];
    for (int64_t f : set) mark[f] = static_cast<uint8_t>(layer);
    layerFaces_ += static_cast<int64_t>(set.size());
    lastLayer_[axis_].insert(lastLayer_[axis_].end(), set.begin(), set.end());
  }
}


// Serial, in the last layer's order, so the list never depends on the workers or the slabs.
void VelocityExtrapolationRun::claimFrontier(int64_t begin, int64_t end) {
  const Eigen::Vector3i d = grid_->faceDims(axis_);
  uint8_t* mark = state_->mark[axis_].data();
  const Array<int64_t>& last = lastLayer_[axis_];
  for (int64_t e = begin; e < end; ++e)
    forFaceNeighbours(d, last[static_cast<size_t>(e)], [&](int64_t n) {
      if (mark[n] != kExtrapolationUnreached) return;
      mark[n] = kClaimed;
      claimed_.push_back(n);
    });
}

void VelocityExtrapolationRun::extrapolateFrontier(int64_t begin, int64_t end) {
  const int layer = layer_;
  const Eigen::Vector3i d = grid_->faceDims(axis_);
  const uint8_t* mark = state_->mark[axis_].data();
  double* u = grid_->velocity[axis_].data();
  const int64_t* faces = claimed_.data();
  parallelFor(*tasks_, end - begin, kRowGrain * d.x(), [&](int64_t first, int64_t last) {
    for (int64_t e = begin + first; e < begin + last; ++e) {
      const int64_t f = faces[e];
      int n;  // >= 1: a face of the last layer is next to it
      u[f] = meanOfSources(mark, u, layer, [&](const auto& visit) { forFaceNeighbours(d, f, visit); }, &n);
    }
  });
}

void VelocityExtrapolationRun::finishFrontier() {
  uint8_t* mark = state_->mark[axis_].data();
  for (int64_t f : claimed_) mark[f] = static_cast<uint8_t>(layer_);
  layerFaces_ += static_cast<int64_t>(claimed_.size());
  lastLayer_[axis_].swap(claimed_);
  claimedAxis_ = false;
}

void VelocityExtrapolationRun::zeroRows(int64_t begin, int64_t end) {
  const int64_t rowLength = grid_->faceDims(axis_).x();
  const uint8_t* mark = state_->mark[axis_].data();
  double* u = grid_->velocity[axis_].data();
  parallelFor(*tasks_, (end - begin) * rowLength, kRowGrain * rowLength, [&](int64_t first, int64_t last) {
    for (int64_t f = begin * rowLength + first; f < begin * rowLength + last; ++f)
      if (mark[f] == kExtrapolationUnreached) u[f] = 0.0;
  });
}

}  // namespace vp
