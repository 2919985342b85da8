// Layered velocity extrapolation (see velocity_extrapolation.h).
#include "fluid/velocity_extrapolation.h"

#include <algorithm>

#include "core/parallel_for.h"
#include "fluid/cut_cell_poisson.h"
#include "fluid/free_surface.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 16;  // face rows (one row = dimX faces) per parallel chunk
constexpr int kMaxLayers = 250;    // marks are bytes; 254 and 255 are reserved

// Calls body(j, k) over the face rows of an axis in parallel.
template <class Body>
void forEachFaceRow(TaskSystem& tasks, const Eigen::Vector3i& dims, const Body& body) {
  parallelFor(tasks, static_cast<int64_t>(dims.z()) * dims.y(), kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row)
      body(static_cast<int>(row % dims.y()), static_cast<int>(row / dims.y()));
  });
}

}  // namespace

Status extrapolateVelocity(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions,
                           const double* liquidPhi, const VelocityExtrapolationSettings& settings,
                           VelocityExtrapolationState& state) {
  if (liquidPhi == nullptr) return fail(Status::InvalidArgument, "velocity extrapolation: liquidPhi is null");
  if (settings.layers < 0 || settings.layers > kMaxLayers)
    return fail(Status::InvalidArgument, "velocity extrapolation: layers = %d must be in [0, %d]", settings.layers,
                kMaxLayers);
  if (!sameGrid(grid.spec, fractions.grid))
    return fail(Status::InvalidArgument, "velocity extrapolation: face fractions belong to another grid");
  const MacGridSpec& g = grid.spec;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid.faceDims(a);
    const int cellsAlong = g.nx * (a == 0) + g.ny * (a == 1) + g.nz * (a == 2);
    std::vector<uint8_t>& mark = state.mark[a];
    mark.resize(grid.velocity[a].size());
    forEachFaceRow(tasks, d, [&](int j, int k) {
      for (int i = 0; i < d.x(); ++i) {
        const size_t f = grid.faceIndex(a, i, j, k);
        if (grid.isWallFace(a, i, j, k)) {
          mark[f] = kExtrapolationFixed;
          continue;
        }
        const double openFraction = effectiveOpenFraction(grid, fractions, a, i, j, k);
        const bool open = openFraction > 0.0;
        Eigen::Vector3i low(i, j, k);
        low[a] -= 1;
        const int along = low[a] + 1;
        const bool liquid = (along > 0 && isLiquid(liquidPhi[grid.cellIndex(low.x(), low.y(), low.z())])) ||
                            (along < cellsAlong && isLiquid(liquidPhi[grid.cellIndex(i, j, k)]));
        if (open && liquid && openFraction >= settings.minSourceOpenFraction) mark[f] = 0;
        else if (open || settings.intoClosedFaces) mark[f] = kExtrapolationUnreached;
        else mark[f] = kExtrapolationFixed;
      }
    });
  }

  // Each layer: a parallel scan writes the new faces' velocities (they are unreached, so no
  // other face of this layer reads them) and lists them per chunk; their marks are set after
  // the scan, so every face of the layer saw the marks of the earlier layers only.
  std::vector<std::vector<int64_t>> assigned;
  for (int layer = 1; layer <= settings.layers; ++layer) {
    int64_t count = 0;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3i d = grid.faceDims(a);
      uint8_t* mark = state.mark[a].data();
      double* u = grid.velocity[a].data();
      const int64_t sy = d.x(), sz = static_cast<int64_t>(d.x()) * d.y();
      const int64_t rows = static_cast<int64_t>(d.z()) * d.y();
      const int64_t chunks = (rows + kRowGrain - 1) / kRowGrain;
      assigned.resize(static_cast<size_t>(chunks));
      parallelFor(tasks, chunks, 1, [&](int64_t firstChunk, int64_t lastChunk) {
        for (int64_t chunk = firstChunk; chunk < lastChunk; ++chunk) {
          std::vector<int64_t>& out = assigned[static_cast<size_t>(chunk)];
          out.clear();
          for (int64_t row = chunk * kRowGrain; row < std::min(rows, (chunk + 1) * kRowGrain); ++row) {
            const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
            const int64_t first = row * sy;
            for (int i = 0; i < d.x(); ++i) {
              const int64_t f = first + i;
              if (mark[f] != kExtrapolationUnreached) continue;
              double sum = 0.0;
              int n = 0;
              auto take = [&](int64_t nb) {
                if (mark[nb] < layer) {
                  sum += u[nb];
                  ++n;
                }
              };
              if (i > 0) take(f - 1);
              if (i + 1 < d.x()) take(f + 1);
              if (j > 0) take(f - sy);
              if (j + 1 < d.y()) take(f + sy);
              if (k > 0) take(f - sz);
              if (k + 1 < d.z()) take(f + sz);
              if (n == 0) continue;
              u[f] = sum / n;
              out.push_back(f);
            }
          }
        }
      });
      for (int64_t chunk = 0; chunk < chunks; ++chunk) {
        for (int64_t f : assigned[static_cast<size_t>(chunk)]) mark[f] = static_cast<uint8_t>(layer);
        count += static_cast<int64_t>(assigned[static_cast<size_t>(chunk)].size());
      }
    }
    if (count == 0) break;  // nothing left within reach
  }
  return Status::Ok;
}

}  // namespace vp
