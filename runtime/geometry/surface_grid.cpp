#include "geometry/surface_grid.h"

#include <algorithm>
#include <cmath>

namespace vp {
namespace {

Status checkSurface(const SurfaceMesh& surface, int resolution, const char* caller) {
  if (resolution < 1 || resolution > kMaxSurfaceGridResolution)
    return fail(Status::InvalidArgument, "%s: resolution %d is outside [1, %d]", caller, resolution,
                kMaxSurfaceGridResolution);
  if (surface.triangles.empty() || surface.vertices.empty())
    return fail(Status::InvalidArgument, "%s: the surface has %zu vertices and %zu triangles", caller,
                surface.vertices.size(), surface.triangles.size());
  for (size_t v = 0; v < surface.vertices.size(); ++v)
    if (!surface.vertices[v].allFinite())
      return fail(Status::InvalidArgument, "%s: surface vertex %zu has a non-finite coordinate", caller, v);
  const int64_t n = static_cast<int64_t>(surface.vertices.size());
  for (size_t t = 0; t < surface.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (surface.triangles[t][k] < 0 || surface.triangles[t][k] >= n)
        return fail(Status::InvalidArgument, "%s: triangle %zu corner %d is vertex %d, outside [0, %lld)", caller, t,
                    k, surface.triangles[t][k], static_cast<long long>(n));
  return Status::Ok;
}

}  // namespace

Status makeSurfaceGrid(const SurfaceMesh& surface, int resolution, const char* caller, SurfaceGrid* out) {
  VP_TRY(checkSurface(surface, resolution, caller));
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
  for (const auto& tri : surface.triangles)
    for (int32_t v : tri) {
      lo = lo.cwiseMin(surface.vertices[v]);
      hi = hi.cwiseMax(surface.vertices[v]);
    }
  const Eigen::Vector3d extent = hi - lo;
  const double longest = extent.maxCoeff();
  if (!(longest > 0.0)) return fail(Status::InvalidArgument, "%s: the surface's bounding box is a single point", caller);

  SurfaceGrid grid;
  grid.cellSize = longest / resolution;
  const double h = grid.cellSize;
  for (int k = 0; k < 3; ++k) {
    // The 1e-9 keeps an extent that is an exact multiple of h (up to round-off) from getting
    // an extra, empty layer; the grid is centred on the box, so it misses at most 0.5e-9 h.
    const double n = std::ceil(extent[k] / h - 1e-9);
    grid.cells[k] = std::max(1, static_cast<int32_t>(std::min<double>(n, kMaxSurfaceGridResolution)));
    grid.origin[k] = 0.5 * (lo[k] + hi[k]) - 0.5 * grid.cells[k] * h;
  }
  const int64_t cells = int64_t(grid.cells[0]) * grid.cells[1] * grid.cells[2];
  if (cells > kMaxSurfaceGridCells)
    return fail(Status::InvalidArgument, "%s: resolution %d gives %lld cells, more than %lld", caller, resolution,
                static_cast<long long>(cells), static_cast<long long>(kMaxSurfaceGridCells));
  *out = grid;
  return Status::Ok;
}

}  // namespace vp
