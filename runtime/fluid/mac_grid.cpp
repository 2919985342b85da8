// MAC grid allocation and velocity sampling (layout in mac_grid.h).
#include "fluid/mac_grid.h"

#include "fluid/advection/grid_sampling.h"

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


double MacGrid::sampleComponent(int axis, const Eigen::Vector3d& point) const {
  // Face centres of `axis` sit at integer grid coordinates along `axis`, half-integer ones
  // along the other two.
  Eigen::Vector3d g = (point - spec.origin) / spec.h - Eigen::Vector3d::Constant(0.5);
  g[axis] += 0.5;
  return trilinearSample(velocity[axis].data(), faceDims(axis), g);
}

double MacGrid::sampleCellCentred(const double* values, const Eigen::Vector3d& point) const {
  const Eigen::Vector3d g = (point - spec.origin) / spec.h - Eigen::Vector3d::Constant(0.5);
  return trilinearSample(values, Eigen::Vector3i(spec.nx, spec.ny, spec.nz), g);
}

Eigen::Vector3d MacGrid::sampleVelocity(const Eigen::Vector3d& point) const {
  return Eigen::Vector3d(sampleComponent(0, point), sampleComponent(1, point), sampleComponent(2, point));
}

}  // namespace vp
