// MAC grid allocation and velocity sampling (layout in mac_grid.h).
#include "fluid/mac_grid.h"

#include <algorithm>
#include <cmath>

namespace vp {

Status initMacGrid(const MacGridSpec& spec, const std::array<DomainSide, 6>& sides, MacGrid* grid) {
  if (grid == nullptr) return fail(Status::InvalidArgument, "mac grid: grid is null");
  if (!(spec.h > 0.0) || !std::isfinite(spec.h))
    return fail(Status::InvalidArgument, "mac grid: cell size h = %g must be positive and finite", spec.h);
  if (spec.nx <= 0 || spec.ny <= 0 || spec.nz <= 0)
    return fail(Status::InvalidArgument, "mac grid: cell counts (nx, ny, nz) = (%d, %d, %d) must be positive",
                spec.nx, spec.ny, spec.nz);
  if (!spec.origin.allFinite())
    return fail(Status::InvalidArgument, "mac grid: origin (%g, %g, %g) must be finite", spec.origin.x(),
                spec.origin.y(), spec.origin.z());
  for (int s = 0; s < 6; ++s)
    if (sides[s] != DomainSide::Wall && sides[s] != DomainSide::Open)
      return fail(Status::InvalidArgument, "mac grid: sides[%d] = %d is neither Wall nor Open", s,
                  static_cast<int>(sides[s]));
  grid->spec = spec;
  grid->sides = sides;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid->faceDims(a);
    grid->velocity[a].assign(static_cast<size_t>(d.x()) * d.y() * d.z(), 0.0);
  }
  return Status::Ok;
}

bool sameGrid(const MacGridSpec& a, const MacGridSpec& b) {
  return a.nx == b.nx && a.ny == b.ny && a.nz == b.nz && a.h == b.h && a.origin == b.origin;
}

namespace {

// Trilinear interpolation of `values` sampled at grid coordinates (0 .. dims-1 per axis,
// index i + dims.x * (j + dims.y * k)) at grid coordinate `g`, clamped to the sample grid.
double trilinear(const double* values, const Eigen::Vector3i& dims, Eigen::Vector3d g) {
  int base[3];
  double weight[3];
  for (int d = 0; d < 3; ++d) {
    // `!(g >= 0)` also catches NaN, whose conversion to int would be undefined.
    if (!(g[d] >= 0.0)) g[d] = 0.0;
    g[d] = std::min(g[d], static_cast<double>(dims[d] - 1));
    const int b = std::min(static_cast<int>(std::floor(g[d])), std::max(dims[d] - 2, 0));
    base[d] = b;
    weight[d] = dims[d] > 1 ? g[d] - b : 0.0;
  }
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    int idx[3];
    double w = 1.0;
    for (int d = 0; d < 3; ++d) {
      const int step = (corner >> d) & 1;
      if (step == 1 && dims[d] == 1) { w = 0.0; break; }
      idx[d] = base[d] + step;
      w *= step ? weight[d] : 1.0 - weight[d];
    }
    if (w == 0.0) continue;
    sum += w * values[static_cast<size_t>(idx[0]) +
                      static_cast<size_t>(dims[0]) * (idx[1] + static_cast<size_t>(dims[1]) * idx[2])];
  }
  return sum;
}

}  // namespace

double MacGrid::sampleComponent(int axis, const Eigen::Vector3d& point) const {
  // Face centres of `axis` sit at integer grid coordinates along `axis`, half-integer ones
  // along the other two.
  Eigen::Vector3d g = (point - spec.origin) / spec.h - Eigen::Vector3d::Constant(0.5);
  g[axis] += 0.5;
  return trilinear(velocity[axis].data(), faceDims(axis), g);
}

double MacGrid::sampleCellCentred(const double* values, const Eigen::Vector3d& point) const {
  const Eigen::Vector3d g = (point - spec.origin) / spec.h - Eigen::Vector3d::Constant(0.5);
  return trilinear(values, Eigen::Vector3i(spec.nx, spec.ny, spec.nz), g);
}

Eigen::Vector3d MacGrid::sampleVelocity(const Eigen::Vector3d& point) const {
  return Eigen::Vector3d(sampleComponent(0, point), sampleComponent(1, point), sampleComponent(2, point));
}

}  // namespace vp
