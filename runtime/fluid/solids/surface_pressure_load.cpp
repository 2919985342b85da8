// Pressure tractions on a deforming surface (see surface_pressure_load.h).
#include "fluid/solids/surface_pressure_load.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "fluid/grid_index.h"
#include "fluid/solids/extended_pressure.h"

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

}  // namespace

void surfacePressureLoad(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                         const CutCellPoisson& op, const double* pressure, const double* liquidPhi, double density,
                         const PreparedCollider& surface, SurfacePressureLoad* out) {
  const Array<Eigen::Vector3d>& x = surface.worldVertices;
  out->vertexForces.assign(x.size(), Vec3::Zero());
  out->total = PressureLoad{};
  LocalPressure local;
  if (!localPressureAround(grid, fractions, op, pressure, liquidPhi, surface.bounds, &surface, &local)) return;
  const MacGridSpec& s = grid.spec;
  const Eigen::Vector3i hi = local.lo + local.dims - Eigen::Vector3i::Ones();
  const Eigen::Vector3i gridHi(s.nx - 1, s.ny - 1, s.nz - 1);
  // False where the point is in a liquid's air (p = 0 there).
  auto wetAt = [&](const Vec3& p) {
    if (liquidPhi == nullptr) return true;
    return !(trilinear(s, Eigen::Vector3i::Zero(), gridHi, p,
                       [&](int i, int j, int k) { return liquidPhi[grid.cellIndex(i, j, k)]; }) > 0.0);
  };
  auto pressureAt = [&](const Vec3& p) {
    return trilinear(s, local.lo, hi, p, [&](int i, int j, int k) {
      return local.value[local.index(Eigen::Vector3i(i, j, k))];
    });
  };
  // Triangle by triangle in parallel, each into its own slot; summed in triangle order after,
  // so the sums do not depend on the worker count.
  struct TriangleLoad {
    Vec3 vertex[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
    double area = 0.0, wetArea = 0.0;
  };
  auto integrate = [&](const Eigen::Vector3i& t, TriangleLoad* load) {
    const Vec3 &a = x[t[0]], &b = x[t[1]], &c = x[t[2]];
    const Vec3 areaVector = 0.5 * (b - a).cross(c - a);  // outward normal times area
    load->area = areaVector.norm();
    const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    const int n = clampIndex(std::ceil(longest / (0.5 * s.h)), 1, kMaxSubdivision);
    const double pieceWeight = 1.0 / (n * n);
    // The pieces' centroids in barycentric (u, v) of b and c: n^2 pieces, upright and inverted.
    auto piece = [&](double u, double v) {
      const Vec3 p = a + u * (b - a) + v * (c - a);
      if (!wetAt(p)) return;
      const double pressureHere = pressureAt(p);
      load->wetArea += pieceWeight * load->area;
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
  Array<TriangleLoad> loads(surface.triangles.size());
  parallelFor(tasks, static_cast<int64_t>(loads.size()), kTriangleGrain, [&](int64_t begin, int64_t end) {
    for (int64_t id = begin; id < end; ++id) {
      const size_t t = static_cast<size_t>(id);
      integrate(surface.triangles[t], &loads[t]);
    }
  });
  double area = 0.0, wetArea = 0.0, volume6 = 0.0;
  for (size_t id = 0; id < loads.size(); ++id) {
    const Eigen::Vector3i& t = surface.triangles[id];
    volume6 += x[t[0]].dot(x[t[1]].cross(x[t[2]]));
    const TriangleLoad& load = loads[id];
    area += load.area;
    wetArea += load.wetArea;
    for (int k = 0; k < 3; ++k) out->vertexForces[t[k]] += load.vertex[k];
    out->total.force += load.force;
    out->total.torque += load.torque;
  }
  if (area > 0.0) out->total.addedMass = density * std::abs(volume6) / 6.0 * wetArea / area;
}

}  // namespace vp
