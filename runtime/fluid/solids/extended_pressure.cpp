// The pressure extended into solids and a liquid's air (see extended_pressure.h).
#include "fluid/solids/extended_pressure.h"

#include <algorithm>
#include <cmath>

#include "collide/mesh_grid_inside.h"
#include "fluid/grid_index.h"

namespace vp {
namespace {

// Air cells beside the liquid: the ghost value of each liquid neighbour, averaged.
void setGhostAirValues(const MacGrid& grid, const CutCellPoisson& op, const double* pressure, const double* phi,
                       LocalPressure& local) {
  const Eigen::Vector3i n(grid.spec.nx, grid.spec.ny, grid.spec.nz);
  for (int k = 0; k < local.dims.z(); ++k)
    for (int j = 0; j < local.dims.y(); ++j)
      for (int i = 0; i < local.dims.x(); ++i) {
        const Eigen::Vector3i c = local.lo + Eigen::Vector3i(i, j, k);
        const int64_t l = local.index(c);
        if (!local.air[l]) continue;
        const double phiAir = phi[grid.cellIndex(c.x(), c.y(), c.z())];
        double sum = 0.0;
        int count = 0;
        for (int a = 0; a < 3; ++a)
          for (int dir = -1; dir <= 1; dir += 2) {
            Eigen::Vector3i nb = c;
            nb[a] += dir;
            if (nb[a] < 0 || nb[a] >= n[a] || !local.contains(nb)) continue;
            const size_t g = grid.cellIndex(nb.x(), nb.y(), nb.z());
            if (!op.isFluid(g) || local.layer[local.index(nb)] != 0 || !(phi[g] < 0.0) || !(phiAir >= 0.0)) continue;
            sum += pressure[g] * phiAir / phi[g];
            ++count;
          }
        if (count > 0) local.value[l] = sum / count;
      }
}

// A cell no fluid can reach: every face closed by colliders or walls.
bool solidCell(const MacGrid& grid, const FaceFractionField& fractions, const Eigen::Vector3i& c) {
  for (int a = 0; a < 3; ++a)
    for (int up = 0; up < 2; ++up) {
      Eigen::Vector3i f = c;
      f[a] += up;
      if (effectiveOpenFraction(grid, fractions, a, f.x(), f.y(), f.z()) > 0.0) return false;
    }
  return true;
}

// Which of the box's cell centres lie inside `body` (none without one), in the box's
// numbering: for a mesh by row parity over the box (collide/mesh_grid_inside.h), one ray per
// row; per centre by solidContains for other shapes and where the rows do not pair up.
Array<uint8_t> cellsInBody(const MacGrid& grid, const PreparedCollider* body, const LocalPressure& local) {
  const int64_t count = int64_t(local.dims.x()) * local.dims.y() * local.dims.z();
  Array<uint8_t> inside;
  if (body == nullptr) {
    inside.assign(static_cast<size_t>(count), 0);
    return inside;
  }
  if (body->shape.kind == ShapeKind::TriangleMesh) {
    SampleGrid centres;
    centres.spacing = grid.spec.h;
    centres.offset = 0.5;
    for (int d = 0; d < 3; ++d) {
      centres.origin[d] = grid.spec.origin[d] + grid.spec.h * local.lo[d];
      centres.count[static_cast<size_t>(d)] = local.dims[d];
    }
    if (meshGridInside(*body, centres, "extended pressure", &inside) == Status::Ok) return inside;
  }
  inside.assign(static_cast<size_t>(count), 0);
  for (int64_t l = 0; l < count; ++l) {
    const Eigen::Vector3i c = local.lo + Eigen::Vector3i(int(l % local.dims.x()), int((l / local.dims.x()) % local.dims.y()),
                                                        int(l / (int64_t(local.dims.x()) * local.dims.y())));
    inside[static_cast<size_t>(l)] = solidContains(*body, grid.cellCentre(c.x(), c.y(), c.z())) ? 1 : 0;
  }
  return inside;
}

void extendIntoSolid(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                     const double* pressure, const double* liquidPhi, const PreparedCollider* body,
                     LocalPressure& local) {
  const int64_t count = int64_t(local.dims.x()) * local.dims.y() * local.dims.z();
  local.value.assign(static_cast<size_t>(count), 0.0);
  local.layer.assign(static_cast<size_t>(count), 0);
  local.air.assign(static_cast<size_t>(count), 0);
  const Array<uint8_t> inBodyCells = cellsInBody(grid, body, local);
  Array<int64_t> unknown;
  for (int k = 0; k < local.dims.z(); ++k)
    for (int j = 0; j < local.dims.y(); ++j)
      for (int i = 0; i < local.dims.x(); ++i) {
        const Eigen::Vector3i c = local.lo + Eigen::Vector3i(i, j, k);
        const int64_t l = local.index(c);
        const size_t g = grid.cellIndex(c.x(), c.y(), c.z());
        const bool inBody = inBodyCells[static_cast<size_t>(l)] != 0;
        if (op.isFluid(g) && !inBody) {
          local.value[l] = pressure[g];
        } else if (inBody || solidCell(grid, fractions, c)) {
          local.layer[l] = -1;
          unknown.push_back(l);
        } else {
          local.air[l] = 1;  // p = 0
        }
      }
  if (liquidPhi != nullptr) setGhostAirValues(grid, op, pressure, liquidPhi, local);
  for (int layer = 1; !unknown.empty(); ++layer) {
    Array<int64_t> still;
    Array<std::pair<int64_t, double>> found;
    for (int64_t l : unknown) {
      const Eigen::Vector3i c = local.lo + Eigen::Vector3i(int(l % local.dims.x()),
                                                          int((l / local.dims.x()) % local.dims.y()),
                                                          int(l / (int64_t(local.dims.x()) * local.dims.y())));
      double sum = 0.0;
      int n = 0;
      for (int a = 0; a < 3; ++a)
        for (int dir = -1; dir <= 1; dir += 2) {
          Eigen::Vector3i nb = c, far = c;
          nb[a] += dir;
          far[a] += 2 * dir;
          if (!local.contains(nb)) continue;
          const int64_t ln = local.index(nb);
          if (local.layer[ln] < 0 || local.layer[ln] >= layer) continue;
          const bool farKnown = local.contains(far) && local.layer[local.index(far)] >= 0 &&
                                local.layer[local.index(far)] < layer;
          sum += farKnown ? 2.0 * local.value[ln] - local.value[local.index(far)] : local.value[ln];
          ++n;
        }
      if (n > 0) found.emplace_back(l, sum / n);
      else still.push_back(l);
    }
    if (found.empty()) break;  // cut off from every known cell: those stay 0
    for (const auto& [l, v] : found) local.value[l] = v, local.layer[l] = layer;
    unknown.swap(still);
  }
}

}  // namespace

bool cellBoxAround(const MacGridSpec& s, const Aabb& bounds, LocalPressure* out) {
  const Eigen::Vector3i n(s.nx, s.ny, s.nz);
  Eigen::Vector3i hi;
  for (int a = 0; a < 3; ++a) {
    // Two cells of margin: the extrapolation reads two known cells outside the body.
    const double l = (std::max(bounds.lo[a], s.origin[a] - s.h) - s.origin[a]) / s.h;
    const double u = (std::min(bounds.hi[a], s.origin[a] + (n[a] + 1) * s.h) - s.origin[a]) / s.h;
    out->lo[a] = clampIndex(std::floor(l) - 2.0, 0, n[a]);
    hi[a] = clampIndex(std::ceil(u) + 2.0, -1, n[a] - 1);
    if (out->lo[a] > hi[a]) return false;
  }
  out->dims = hi - out->lo + Eigen::Vector3i::Ones();
  return true;
}

bool localPressureAround(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                         const double* pressure, const double* liquidPhi, const Aabb& bounds,
                         const PreparedCollider* body, LocalPressure* out) {
  LocalPressure local;
  if (!cellBoxAround(grid.spec, bounds, &local)) return false;
  extendIntoSolid(grid, fractions, op, pressure, liquidPhi, body, local);
  *out = std::move(local);
  return true;
}

}  // namespace vp
