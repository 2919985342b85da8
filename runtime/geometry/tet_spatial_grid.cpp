#include "geometry/tet_spatial_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vp {

void TetSpatialGrid::build(const TetMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  double meanExtent = 0.0;
  for (const auto& tet : mesh.tets) {
    Eigen::Vector3d tlo = mesh.vertices[tet[0]], thi = tlo;
    for (int k = 1; k < 4; ++k) {
      tlo = tlo.cwiseMin(mesh.vertices[tet[k]]);
      thi = thi.cwiseMax(mesh.vertices[tet[k]]);
    }
    lo = lo.cwiseMin(tlo);
    hi = hi.cwiseMax(thi);
    meanExtent += (thi - tlo).maxCoeff();
  }
  if (mesh.tets.empty()) {
    lo = hi = Eigen::Vector3d::Zero();
  } else {
    meanExtent /= static_cast<double>(mesh.tets.size());
  }
  const Eigen::Vector3d extent = hi - lo;
  // About one tet extent per cell; never more cells than ~8 per tet (memory), never a
  // zero size (flat or single-point input).
  cellSize_ = std::max({meanExtent, extent.maxCoeff() * 1e-6, std::numeric_limits<double>::min()});
  const double maxCells = 8.0 * static_cast<double>(mesh.tets.size()) + 64.0;
  for (;;) {
    double total = 1.0;
    for (int a = 0; a < 3; ++a) total *= std::floor(extent[a] / cellSize_) + 1.0;
    if (total <= maxCells) break;
    cellSize_ *= 1.25;
  }
  origin_ = lo;
  for (int a = 0; a < 3; ++a) cells_[a] = static_cast<int64_t>(std::floor(extent[a] / cellSize_)) + 1;

  // Two passes (count, then fill) give a compact CSR layout.
  const int64_t numCells = cells_[0] * cells_[1] * cells_[2];
  cellStart_.assign(static_cast<size_t>(numCells + 1), 0);
  auto forEachCellOfTet = [&](const std::array<int32_t, 4>& tet, auto visit) {
    Eigen::Vector3d tlo = mesh.vertices[tet[0]], thi = tlo;
    for (int k = 1; k < 4; ++k) {
      tlo = tlo.cwiseMin(mesh.vertices[tet[k]]);
      thi = thi.cwiseMax(mesh.vertices[tet[k]]);
    }
    const auto a = cellOf(tlo), b = cellOf(thi);
    for (int64_t k = a[2]; k <= b[2]; ++k)
      for (int64_t j = a[1]; j <= b[1]; ++j)
        for (int64_t i = a[0]; i <= b[0]; ++i) visit((k * cells_[1] + j) * cells_[0] + i);
  };
  for (const auto& tet : mesh.tets) forEachCellOfTet(tet, [&](int64_t c) { ++cellStart_[c + 1]; });
  for (int64_t c = 0; c < numCells; ++c) cellStart_[c + 1] += cellStart_[c];
  tets_.assign(static_cast<size_t>(cellStart_[numCells]), 0);
  Array<int64_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    forEachCellOfTet(mesh.tets[t], [&](int64_t c) { tets_[fill[c]++] = static_cast<int32_t>(t); });
}

std::array<int64_t, 3> TetSpatialGrid::cellOf(const Eigen::Vector3d& p) const {
  std::array<int64_t, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double x = std::floor((p[a] - origin_[a]) / cellSize_);
    // Clamp in double first: x may be huge or NaN-free but far outside the int64 range.
    c[a] = static_cast<int64_t>(std::clamp(x, 0.0, static_cast<double>(cells_[a] - 1)));
  }
  return c;
}

double TetSpatialGrid::distanceBeyondRing(const Eigen::Vector3d& p, const std::array<int64_t, 3>& centre,
                                          int64_t ring) const {
  double bound = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const int64_t below = centre[a] - ring - 1;  // first cell layer beyond the ring
    const int64_t above = centre[a] + ring + 1;
    if (below >= 0) bound = std::min(bound, std::max(0.0, p[a] - (origin_[a] + (below + 1) * cellSize_)));
    if (above < cells_[a]) bound = std::min(bound, std::max(0.0, (origin_[a] + above * cellSize_) - p[a]));
  }
  return bound;
}

}  // namespace vp
