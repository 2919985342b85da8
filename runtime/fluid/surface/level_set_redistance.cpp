// Narrow-band redistancing (see level_set_redistance.h).
#include "fluid/surface/level_set_redistance.h"
#include "fluid/solids/sliver_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel_for.h"
#include "core/slab_passes.h"
#include "fluid/cell_lattice.h"
#include "fluid/surface/free_surface.h"
#include "gpu_kernels/level_set_kernels.h"

namespace vp {
namespace {

constexpr int64_t kCellGrain = 8192;
constexpr int64_t kListGrain = 2048;
constexpr uint8_t kOutside = 255;

struct Lattice {
  int64_t nx, ny, nz, sy, sz;
  explicit Lattice(const MacGridSpec& g)
      : nx(g.nx), ny(g.ny), nz(g.nz), sy(g.nx), sz(static_cast<int64_t>(g.nx) * g.ny) {}
  void coordinates(int64_t c, int64_t* i, int64_t* j, int64_t* k) const {
    *i = c % nx;
    *j = (c / nx) % ny;
    *k = c / sz;
  }
  // visit(neighbour) for the 6-neighbours inside the grid.
  template <class Visit>
  void forNeighbours(int64_t c, const Visit& visit) const {
    int64_t i, j, k;
    coordinates(c, &i, &j, &k);
    forNeighbours(c, i, j, k, visit);
  }
  // The same for cell c = (i, j, k).
  template <class Visit>
  void forNeighbours(int64_t c, int64_t i, int64_t j, int64_t k, const Visit& visit) const {
    if (i > 0) visit(c - 1);
    if (i + 1 < nx) visit(c + 1);
    if (j > 0) visit(c - sy);
    if (j + 1 < ny) visit(c + sy);
    if (k > 0) visit(c - sz);
    if (k + 1 < nz) visit(c + sz);
  }
};

struct MaxDrop {
  double value = 0.0;
  MaxDrop& operator+=(const MaxDrop& o) {
    value = std::max(value, o.value);
    return *this;
  }
};

}  // namespace

Status redistanceLevelSet(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const RedistanceSettings& settings,
                          RedistanceWorkspace& ws, RedistanceStats* stats) {
  RedistanceRun run;
  VP_TRY(run.prepare(tasks, grid, phi, settings, ws, std::numeric_limits<int64_t>::max()));
  while (!run.advance()) {
  }
  if (stats != nullptr) *stats = run.stats();
  return Status::Ok;
}

Status RedistanceRun::prepare(TaskSystem& tasks, const MacGridSpec& grid, double* phi,
                              const RedistanceSettings& settings, RedistanceWorkspace& ws, int64_t samplesPerSlice,
                              const double* cellWeights) {
  pass_ = Pass::Done;
  if (phi == nullptr) return fail(Status::InvalidArgument, "redistance: phi is null");
  const int64_t cells = static_cast<int64_t>(grid.nx) * grid.ny * grid.nz;
  if (cells <= 0 || cells > std::numeric_limits<int32_t>::max() || !(grid.h > 0.0))
    return fail(Status::InvalidArgument, "redistance: grid (%d, %d, %d, h %g) is empty or too large", grid.nx,
                grid.ny, grid.nz, grid.h);
  const int layers = static_cast<int>(std::ceil(std::sqrt(3.0) * settings.bandCells)) + 1;
  if (!(settings.bandCells >= 1.0) || layers >= kOutside || !(settings.tolerance > 0.0) || settings.maxSweeps < 1)
    return fail(Status::InvalidArgument,
                "redistance: bandCells = %g must be in [1, 140], tolerance = %g positive, maxSweeps = %d >= 1",
                settings.bandCells, settings.tolerance, settings.maxSweeps);
  if (samplesPerSlice < 1)
    return fail(Status::InvalidArgument, "redistance: samplesPerSlice = %lld must be >= 1",
                static_cast<long long>(samplesPerSlice));
  tasks_ = &tasks;
  grid_ = grid;
  phi_ = phi;
  cellWeights_ = cellWeights;
  settings_ = settings;
  ws_ = &ws;
  samplesPerSlice_ = samplesPerSlice;
  cells_ = cells;
  layers_ = layers;
  ws.distance.resize(static_cast<size_t>(cells));
  ws.layer.resize(static_cast<size_t>(cells));
  ws.stale.resize(static_cast<size_t>(cells));
  ws.surface.clear();
  ws.band[0].clear();
  ws.band[1].clear();
  ws.reached.clear();
  pass_ = Pass::Surface;
  position_ = 0;
  colour_ = 0;
  drop_ = 0.0;
  stats_ = RedistanceStats{};
  lastSliceSamples_ = 0;
  return Status::Ok;
}

bool RedistanceRun::advance() {
  lastSliceSamples_ = runSamplesUpTo(
      samplesPerSlice_, [this] { return pass_ == Pass::Done; }, [this](int64_t left) { return step(left); });
  return pass_ == Pass::Done;
}

int64_t RedistanceRun::step(int64_t budget) {
  if (pass_ == Pass::Band) return claimBand(budget);
  const int64_t length = pass_ == Pass::Sweep ? static_cast<int64_t>(ws_->band[colour_].size()) : cells_;
  const int64_t begin = position_, end = begin + std::min(budget, length - begin);
  position_ = end;
  if (pass_ == Pass::Surface) {
    detectSurface(begin, end);
    if (end == length) {
      ws_->reached = ws_->surface;
      pass_ = Pass::Band;
      position_ = 0;
    }
  } else if (pass_ == Pass::List) {
    listBand(begin, end);
    if (end == length) {
      pass_ = Pass::Sweep;
      position_ = 0;
    }
  } else if (pass_ == Pass::Sweep) {
    drop_ = std::max(drop_, sweepSlab(begin, end));
    if (end == length) finishSweep();
  } else {
    writeSlab(begin, end);
    if (end == length) {
      stats_.surfaceCells = static_cast<int64_t>(ws_->surface.size());
      stats_.bandCells = static_cast<int64_t>(ws_->band[0].size() + ws_->band[1].size());
      pass_ = Pass::Done;
    }
  }
  return end - begin;
}

// 1. Surface cells and their subcell distances; everything else starts at +inf. The surface
// list stays in cell order: slabs are consecutive and their chunks are appended in order.
void RedistanceRun::detectSurface(int64_t begin, int64_t end) {
  const Lattice lat(grid_);
  const double h = grid_.h;
  const double* phi = phi_;
  double* dist = ws_->distance.data();
  uint8_t* layer = ws_->layer.data();
  const int64_t chunks = (end - begin + kCellGrain - 1) / kCellGrain;
  const double* weights = cellWeights_;
  auto covered = [weights](int64_t cell) { return weights != nullptr && weights[cell] < kSliverCellWeight; };
  std::vector<Array<int32_t>>& found = ws_->chunkSurface;
  if (static_cast<int64_t>(found.size()) < chunks) found.resize(static_cast<size_t>(chunks));
  parallelFor(*tasks_, chunks, 1, [&](int64_t first, int64_t last) {
    for (int64_t chunk = first; chunk < last; ++chunk) {
      Array<int32_t>& out = found[static_cast<size_t>(chunk)];
      out.clear();
      const int64_t chunkBegin = begin + chunk * kCellGrain, chunkEnd = std::min(end, chunkBegin + kCellGrain);
      forCellsInRange(grid_, chunkBegin, chunkEnd, [&](int64_t c, int i, int j, int k) {
        const bool liquid = isLiquid(phi[c]);
        bool surface = false;
        if (!covered(c))
          lat.forNeighbours(c, i, j, k,
                            [&](int64_t n) { surface = surface || (!covered(n) && isLiquid(phi[n]) != liquid); });
        if (!surface) {
          dist[c] = kernels::unreachedDistance();
          layer[c] = kOutside;
          return;
        }
        const int64_t ijk[3] = {i, j, k};
        const int64_t count[3] = {lat.nx, lat.ny, lat.nz}, stride[3] = {1, lat.sy, lat.sz};
        double gradient2 = 0.0;
        for (int a = 0; a < 3; ++a) {
          const bool hasMinus = ijk[a] > 0 && !covered(c - stride[a]);
          const bool hasPlus = ijk[a] + 1 < count[a] && !covered(c + stride[a]);
          const double minus = hasMinus ? phi[c] - phi[c - stride[a]] : 0.0;
          const double plus = hasPlus ? phi[c + stride[a]] - phi[c] : 0.0;
          const bool both = hasMinus && hasPlus;
          // Central where phi is monotone along the axis (O(h^2)); the larger one-sided
          // difference at an extremum (a thin sheet), where the central one would vanish.
          const double slope = (both && minus * plus > 0.0 ? 0.5 * std::fabs(plus + minus)
                                                           : std::max(std::fabs(minus), std::fabs(plus))) / h;
          gradient2 += slope * slope;
        }
        // A sign change along some axis makes the gradient nonzero; the max keeps d <= h.
        const double d = gradient2 > 0.0 ? std::fabs(phi[c]) / std::sqrt(gradient2) : h;
        dist[c] = std::min(d, h);
        layer[c] = 0;
        out.push_back(static_cast<int32_t>(c));
      });
    }
  });
  for (int64_t chunk = 0; chunk < chunks; ++chunk) {
    const Array<int32_t>& part = found[static_cast<size_t>(chunk)];
    ws_->surface.insert(ws_->surface.end(), part.begin(), part.end());
  }
}

// 2. Band layers: breadth-first from the surface cells, each cell claimed once, by the first
// queue entry that reaches it; the queue holds the layers in order, so a cell of the last
// layer ends the search.
int64_t RedistanceRun::claimBand(int64_t budget) {
  const Lattice lat(grid_);
  uint8_t* layer = ws_->layer.data();
  Array<int32_t>& queue = ws_->reached;
  int64_t done = 0;
  for (; done < budget && position_ < static_cast<int64_t>(queue.size()); ++done, ++position_) {
    const int32_t c = queue[static_cast<size_t>(position_)];
    const int next = layer[c] + 1;
    if (next > layers_) {
      position_ = static_cast<int64_t>(queue.size());
      break;
    }
    lat.forNeighbours(c, [&](int64_t n) {
      if (layer[n] != kOutside) return;
      layer[n] = static_cast<uint8_t>(next);
      queue.push_back(static_cast<int32_t>(n));
    });
  }
  if (position_ == static_cast<int64_t>(queue.size())) {
    pass_ = Pass::List;
    position_ = 0;
  }
  return done;
}

// The band cells of [begin, end) (layers 1 and up), appended to their colour's list in cell
// order: a sweep then walks the grid's memory in order instead of the search's.
void RedistanceRun::listBand(int64_t begin, int64_t end) {
  const Lattice lat(grid_);
  const uint8_t* layer = ws_->layer.data();
  uint8_t* stale = ws_->stale.data();
  const int64_t chunks = (end - begin + kCellGrain - 1) / kCellGrain;
  std::vector<Array<int32_t>>& found = ws_->chunkBand;
  if (static_cast<int64_t>(found.size()) < 2 * chunks) found.resize(static_cast<size_t>(2 * chunks));
  parallelFor(*tasks_, chunks, 1, [&](int64_t first, int64_t last) {
    for (int64_t chunk = first; chunk < last; ++chunk) {
      Array<int32_t>* out = &found[static_cast<size_t>(2 * chunk)];
      out[0].clear();
      out[1].clear();
      const int64_t chunkEnd = std::min(end, begin + (chunk + 1) * kCellGrain);
      for (int64_t c = begin + chunk * kCellGrain; c < chunkEnd; ++c) {
        if (layer[c] == 0 || layer[c] == kOutside) continue;
        int64_t i, j, k;
        lat.coordinates(c, &i, &j, &k);
        out[(i + j + k) & 1].push_back(static_cast<int32_t>(c));
        // Only the first layer has a neighbour with a distance (a surface cell) before the sweeps.
        stale[c] = layer[c] == 1 ? 1 : 0;
      }
    }
  });
  for (int64_t part = 0; part < 2 * chunks; ++part) {
    const Array<int32_t>& cells = found[static_cast<size_t>(part)];
    Array<int32_t>& band = ws_->band[part & 1];
    band.insert(band.end(), cells.begin(), cells.end());
  }
}

// 3. Red-black Gauss-Seidel on the eikonal equation: entries [begin, end) of the running
// half-sweep's colour. Returns their largest drop.
double RedistanceRun::sweepSlab(int64_t begin, int64_t end) {
  const kernels::CellLattice lattice = cellLattice(grid_);
  const double clamp = settings_.bandCells * grid_.h;
  double* dist = ws_->distance.data();
  uint8_t* stale = ws_->stale.data();
  const int32_t* list = ws_->band[colour_].data() + begin;
  return parallelReduce<MaxDrop>(*tasks_, end - begin, kListGrain, [&](int64_t first, int64_t last) {
    MaxDrop part;
    for (int64_t b = first; b < last; ++b)
      part.value = std::max(part.value, kernels::redistanceSweepStaleCell(lattice, list[b], clamp, dist, stale));
    return part;
  }).value;
}

// After a half-sweep: the other colour, or after both the convergence test.
void RedistanceRun::finishSweep() {
  position_ = 0;
  colour_ = 1 - colour_;
  if (colour_ == 1) return;
  ++stats_.sweeps;
  if (drop_ <= settings_.tolerance * grid_.h) stats_.converged = true;
  if (stats_.converged || stats_.sweeps >= settings_.maxSweeps) pass_ = Pass::Write;
  drop_ = 0.0;
}

// 4. Signed, clamped result.
void RedistanceRun::writeSlab(int64_t begin, int64_t end) {
  const double clamp = settings_.bandCells * grid_.h;
  const double* dist = ws_->distance.data();
  double* phi = phi_;
  parallelFor(*tasks_, end - begin, kCellGrain, [&](int64_t first, int64_t last) {
    for (int64_t c = begin + first; c < begin + last; ++c) kernels::writeSignedDistance(c, dist[c], clamp, phi);
  });
}

}  // namespace vp
