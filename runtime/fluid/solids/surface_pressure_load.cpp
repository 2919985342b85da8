// Pressure tractions on a deforming surface (see surface_pressure_load.h).
#include "fluid/solids/surface_pressure_load.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/parallel_for.h"
#include "fluid/grid_index.h"
#include "fluid/solids/extended_pressure.h"
#include "fluid/surface/hydrostatic_pressure.h"

namespace vp {
namespace {

// Trilinear interpolation of cell-centred values at x; `at(i, j, k)` reads one cell, the
// indices clamped to [lo, hi].
template <class At>
double trilinear(const MacGridSpec& s, const Eigen::Vector3i& lo, const Eigen::Vector3i& hi, const Vec3& x,
                 const At& at) {
  int i0[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    const double c = (x[a] - s.origin[a]) / s.h - 0.5;
    const double f = std::floor(c);
    i0[a] = clampIndex(f, lo[a], std::max(lo[a], hi[a] - 1));
    t[a] = std::clamp(c - i0[a], 0.0, 1.0);
  }
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    double w = 1.0;
    int idx[3];
    for (int a = 0; a < 3; ++a) {
      const int up = (corner >> a) & 1;
      idx[a] = std::min(i0[a] + up, hi[a]);
      w *= up ? t[a] : 1.0 - t[a];
    }
    if (w != 0.0) sum += w * at(idx[0], idx[1], idx[2]);
  }
  return sum;
}

// Triangles per parallel chunk: each is a few dozen interpolations.
constexpr int64_t kTriangleGrain = 16;

// One triangle's part of a traction integral.
struct TriangleLoad {
  Vec3 vertex[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
  double area = 0.0, wetArea = 0.0;
};

// The traction -p n over each triangle by the midpoint rule on pieces of edge at most half of
// cellSize (surface_pressure_load.h), in parallel, each triangle into its own slot.
// pressureAt(point, &p) sets the pressure there (0: no traction) and returns whether the point
// is wetted (it counts in the wetted area).
template <class PressureAt>
Array<TriangleLoad> integrateTractions(TaskSystem& tasks, const Array<Eigen::Vector3d>& x,
                                       const Array<Eigen::Vector3i>& triangles, double cellSize,
                                       const PressureAt& pressureAt) {
  auto integrate = [&](const Eigen::Vector3i& t, TriangleLoad* load) {
    const Vec3 &a = x[t[0]], &b = x[t[1]], &c = x[t[2]];
    const Vec3 areaVector = 0.5 * (b - a).cross(c - a);  // outward normal times area
    load->area = areaVector.norm();
    const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    const int n = clampIndex(std::ceil(longest / (0.5 * cellSize)), 1, kMaxSubdivision);
    const double pieceWeight = 1.0 / (n * n);
    // The pieces' centroids in barycentric (u, v) of b and c: n^2 pieces, upright and inverted.
    auto piece = [&](double u, double v) {
      const Vec3 p = a + u * (b - a) + v * (c - a);
      double pressureHere = 0.0;
      if (pressureAt(p, &pressureHere)) load->wetArea += pieceWeight * load->area;
      if (pressureHere == 0.0) return;
      const Vec3 f = -pressureHere * pieceWeight * areaVector;
      load->vertex[0] += (1.0 - u - v) * f;
      load->vertex[1] += u * f;
      load->vertex[2] += v * f;
      load->force += f;
      load->torque += p.cross(f);
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        piece((i + 1.0 / 3.0) / n, (j + 1.0 / 3.0) / n);
        if (i + j + 1 < n) piece((i + 2.0 / 3.0) / n, (j + 2.0 / 3.0) / n);
      }
  };
  Array<TriangleLoad> loads(triangles.size());
  parallelFor(tasks, static_cast<int64_t>(loads.size()), kTriangleGrain, [&](int64_t begin, int64_t end) {
    for (int64_t id = begin; id < end; ++id) {
      const size_t t = static_cast<size_t>(id);
      integrate(triangles[t], &loads[t]);
    }
  });
  return loads;
}

// The triangles' vertex forces summed into one per vertex, in triangle order (so the sums do
// not depend on the worker count).
void gatherVertexForces(const Array<Eigen::Vector3i>& triangles, const Array<TriangleLoad>& loads, size_t vertices,
                        Array<Vec3>* out) {
  out->assign(vertices, Vec3::Zero());
  for (size_t id = 0; id < loads.size(); ++id)
    for (int k = 0; k < 3; ++k) (*out)[triangles[id][k]] += loads[id].vertex[k];
}

}  // namespace

void surfacePressureLoad(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                         const CutCellPoisson& op, const double* pressure, const double* liquidPhi, double density,
                         const PreparedCollider& surface, SurfacePressureLoad* out, const LiquidWeight* less) {
  const Array<Eigen::Vector3d>& x = surface.worldVertices;
  out->vertexForces.assign(x.size(), Vec3::Zero());
  out->total = PressureLoad{};
  LocalPressure local;
  if (!localPressureAround(grid, fractions, op, pressure, liquidPhi, surface.bounds, &surface, &local)) return;
  const MacGridSpec& s = grid.spec;
  const Eigen::Vector3i hi = local.lo + local.dims - Eigen::Vector3i::Ones();
  const Eigen::Vector3i gridHi(s.nx - 1, s.ny - 1, s.nz - 1);
  std::optional<HydrostaticPressure> hydrostatic;
  if (less != nullptr && less->liquidPhi != nullptr)
    hydrostatic.emplace(grid, less->liquidPhi, density, less->gravity, surface.bounds);
  // Dry where the point is in a liquid's air (p = 0 there).
  auto phiAt = [&](const Vec3& p) {
    return trilinear(s, Eigen::Vector3i::Zero(), gridHi, p, [&](int i, int j, int k) {
      return liquidPhi[grid.cellIndex(i, j, k)];
    });
  };
  auto solvedAt = [&](const Vec3& p) {
    return trilinear(s, local.lo, hi, p, [&](int i, int j, int k) {
      return local.value[local.index(Eigen::Vector3i(i, j, k))];
    });
  };
  auto pressureAt = [&](const Vec3& p, double* value) {
    const bool wet = liquidPhi == nullptr || !(phiAt(p) > 0.0);
    *value = (wet ? solvedAt(p) : 0.0) - (hydrostatic ? hydrostatic->at(p) : 0.0);
    return wet;
  };
  const Array<TriangleLoad> loads = integrateTractions(tasks, x, surface.triangles, s.h, pressureAt);
  gatherVertexForces(surface.triangles, loads, x.size(), &out->vertexForces);
  double area = 0.0, wetArea = 0.0, volume6 = 0.0;
  for (size_t id = 0; id < loads.size(); ++id) {
    const Eigen::Vector3i& t = surface.triangles[id];
    volume6 += x[t[0]].dot(x[t[1]].cross(x[t[2]]));
    area += loads[id].area;
    wetArea += loads[id].wetArea;
    out->total.force += loads[id].force;
    out->total.torque += loads[id].torque;
  }
  if (area > 0.0) out->total.addedMass = density * std::abs(volume6) / 6.0 * wetArea / area;
}

void surfaceHydrostaticLoad(TaskSystem& tasks, const MacGrid& grid, const double* liquidPhi, double density,
                            const Vec3& gravity, const Array<Eigen::Vector3d>& vertices,
                            const Array<Eigen::Vector3i>& triangles, Array<Vec3>* vertexForces) {
  if (liquidPhi == nullptr || vertices.empty()) {
    vertexForces->assign(vertices.size(), Vec3::Zero());
    return;
  }
  Aabb bounds{vertices[0], vertices[0]};
  for (const Eigen::Vector3d& v : vertices) {
    bounds.lo = bounds.lo.cwiseMin(v);
    bounds.hi = bounds.hi.cwiseMax(v);
  }
  const HydrostaticPressure hydrostatic(grid, liquidPhi, density, gravity, bounds);
  auto pressureAt = [&](const Vec3& p, double* value) {
    *value = hydrostatic.at(p);
    return *value > 0.0;
  };
  gatherVertexForces(triangles, integrateTractions(tasks, vertices, triangles, grid.spec.h, pressureAt),
                     vertices.size(), vertexForces);
}

}  // namespace vp
