// Narrow-band redistancing (see level_set_redistance.h).
#include "fluid/level_set_redistance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel_for.h"
#include "fluid/free_surface.h"

namespace vp {
namespace {

constexpr int64_t kCellGrain = 8192;
constexpr int64_t kListGrain = 2048;
constexpr uint8_t kOutside = 255;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

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

// Godunov upwind solution of |grad d| = 1 from the smaller neighbour value along each axis.
double eikonalUpdate(double a, double b, double c, double h) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  double d = a + h;
  if (d <= b) return d;
  d = 0.5 * (a + b + std::sqrt(2.0 * h * h - (a - b) * (a - b)));
  if (d <= c) return d;
  const double s = a + b + c;
  return (s + std::sqrt(s * s - 3.0 * (a * a + b * b + c * c - h * h))) / 3.0;
}

}  // namespace

Status redistanceLevelSet(TaskSystem& tasks, const MacGridSpec& grid, double* phi, const RedistanceSettings& settings,
                          RedistanceWorkspace& ws, RedistanceStats* stats) {
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
  const Lattice lat(grid);
  const double h = grid.h;
  ws.distance.resize(static_cast<size_t>(cells));
  ws.layer.resize(static_cast<size_t>(cells));
  double* dist = ws.distance.data();
  uint8_t* layer = ws.layer.data();

  // 1. Surface cells and their subcell distances; everything else starts at +inf.
  const int64_t chunks = (cells + kCellGrain - 1) / kCellGrain;
  std::vector<std::vector<int32_t>> found(static_cast<size_t>(chunks));
  parallelFor(tasks, chunks, 1, [&](int64_t first, int64_t last) {
    for (int64_t chunk = first; chunk < last; ++chunk) {
      std::vector<int32_t>& out = found[static_cast<size_t>(chunk)];
      out.clear();
      const int64_t end = std::min(cells, (chunk + 1) * kCellGrain);
      for (int64_t c = chunk * kCellGrain; c < end; ++c) {
        const bool liquid = isLiquid(phi[c]);
        bool surface = false;
        lat.forNeighbours(c, [&](int64_t n) { surface = surface || isLiquid(phi[n]) != liquid; });
        if (!surface) {
          dist[c] = kInfinity;
          layer[c] = kOutside;
          continue;
        }
        int64_t ijk[3];
        lat.coordinates(c, &ijk[0], &ijk[1], &ijk[2]);
        const int64_t count[3] = {lat.nx, lat.ny, lat.nz}, stride[3] = {1, lat.sy, lat.sz};
        double gradient2 = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double minus = ijk[a] > 0 ? phi[c] - phi[c - stride[a]] : 0.0;
          const double plus = ijk[a] + 1 < count[a] ? phi[c + stride[a]] - phi[c] : 0.0;
          const bool both = ijk[a] > 0 && ijk[a] + 1 < count[a];
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
      }
    }
  });
  ws.surface.clear();
  for (const auto& part : found) ws.surface.insert(ws.surface.end(), part.begin(), part.end());

  // 2. Band layers (serial breadth-first: each cell is claimed once, in a fixed order).
  ws.band[0].clear();
  ws.band[1].clear();
  std::vector<int32_t> frontier = ws.surface, next;
  for (int l = 1; l <= layers && !frontier.empty(); ++l) {
    next.clear();
    for (int32_t c : frontier)
      lat.forNeighbours(c, [&](int64_t n) {
        if (layer[n] != kOutside) return;
        layer[n] = static_cast<uint8_t>(l);
        next.push_back(static_cast<int32_t>(n));
      });
    for (int32_t c : next) {
      int64_t i, j, k;
      lat.coordinates(c, &i, &j, &k);
      ws.band[(i + j + k) & 1].push_back(c);
    }
    frontier.swap(next);
  }

  // 3. Red-black Gauss-Seidel on the eikonal equation.
  int sweeps = 0;
  bool converged = false;
  auto halfSweep = [&](const std::vector<int32_t>& list) {
    return parallelReduce<MaxDrop>(tasks, static_cast<int64_t>(list.size()), kListGrain, [&](int64_t begin, int64_t end) {
      MaxDrop drop;
      for (int64_t b = begin; b < end; ++b) {
        const int64_t c = list[static_cast<size_t>(b)];
        int64_t ijk[3];
        lat.coordinates(c, &ijk[0], &ijk[1], &ijk[2]);
        const int64_t count[3] = {lat.nx, lat.ny, lat.nz}, stride[3] = {1, lat.sy, lat.sz};
        double upwind[3];
        for (int a = 0; a < 3; ++a) {
          const double minus = ijk[a] > 0 ? dist[c - stride[a]] : kInfinity;
          const double plus = ijk[a] + 1 < count[a] ? dist[c + stride[a]] : kInfinity;
          upwind[a] = std::min(minus, plus);
        }
        if (std::isinf(std::min({upwind[0], upwind[1], upwind[2]}))) continue;  // not reached yet
        const double updated = eikonalUpdate(upwind[0], upwind[1], upwind[2], h);
        if (updated < dist[c]) {
          if (!std::isinf(dist[c])) drop.value = std::max(drop.value, dist[c] - updated);
          else drop.value = kInfinity;
          dist[c] = updated;
        }
      }
      return drop;
    });
  };
  while (sweeps < settings.maxSweeps) {
    const double red = halfSweep(ws.band[0]).value, black = halfSweep(ws.band[1]).value;
    ++sweeps;
    if (std::max(red, black) <= settings.tolerance * h) {
      converged = true;
      break;
    }
  }

  // 4. Signed, clamped result.
  const double clamp = settings.bandCells * h;
  parallelFor(tasks, cells, kCellGrain, [&](int64_t begin, int64_t end) {
    for (int64_t c = begin; c < end; ++c) {
      const double d = std::min(dist[c], clamp);
      phi[c] = isLiquid(phi[c]) ? -d : d;
    }
  });
  if (stats != nullptr) {
    stats->surfaceCells = static_cast<int64_t>(ws.surface.size());
    stats->bandCells = static_cast<int64_t>(ws.band[0].size() + ws.band[1].size());
    stats->sweeps = sweeps;
    stats->converged = converged;
  }
  return Status::Ok;
}

}  // namespace vp
