#include "geometry/voxel_tetrahedralizer.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <utility>
#include <vector>

namespace vp {
namespace {

constexpr int kMaxResolution = 1024;
constexpr int64_t kMaxCells = int64_t(1) << 24;

// ---- inside test ----------------------------------------------------------------------
//
// Why ray parity along grid rows and not the generalized winding number: the GWN is the
// better answer for broken meshes, but it costs O(cells x triangles) (a 64^3 grid against a
// 100K-triangle render mesh is 2.6e10 solid angles). Casting one ray per grid row through
// the cell centres costs O(rows + triangles + crossings), and on a closed surface it is
// exact when the 2D point-in-triangle test is made consistent: the ray through a shared
// edge or vertex is exactly where naive parity breaks (and grid-aligned inputs hit edges
// all the time). We decide such ties by symbolic perturbation of the ray, and evaluate each
// edge with its endpoints in a canonical order, so the two triangles that share an edge
// see bit-identical values of opposite sign: exactly one of them claims the ray. A row with
// an odd number of crossings can then only come from a surface with a hole, which we
// report instead of guessing.

using Vec2 = Eigen::Vector2d;

// Sign of the orientation of q relative to the directed edge a->b, with q perturbed by
// (eps, eps^2) when it lies exactly on the line; 0 only when a == b.
int perturbedEdgeSign(const Vec2& a, const Vec2& b, const Vec2& q, double* value) {
  const bool flip = std::make_pair(a.x(), a.y()) > std::make_pair(b.x(), b.y());
  const Vec2& p0 = flip ? b : a;
  const Vec2& p1 = flip ? a : b;
  double e = (p1.x() - p0.x()) * (q.y() - p0.y()) - (p1.y() - p0.y()) * (q.x() - p0.x());
  if (flip) e = -e;
  *value = e;
  if (e > 0) return 1;
  if (e < 0) return -1;
  // d/d(eps) of the orientation for q + (eps, eps^2): -(b.y - a.y) first, then (b.x - a.x).
  if (b.y() != a.y()) return b.y() < a.y() ? 1 : -1;
  if (b.x() != a.x()) return b.x() > a.x() ? 1 : -1;
  return 0;
}

struct Crossing {
  int64_t row;
  double x;
  bool operator<(const Crossing& o) const { return row != o.row ? row < o.row : x < o.x; }
};

// ---- surface cells ----------------------------------------------------------------------

// Separating-axis triangle/box overlap test (Akenine-Moeller 2001): the 3 box axes, the
// triangle normal and the 9 edge x axis cross products. Touching counts as overlap.
bool triangleOverlapsBox(const Eigen::Vector3d& centre, const Eigen::Vector3d& half, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d v[3] = {a - centre, b - centre, c - centre};
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({v[0][k], v[1][k], v[2][k]});
    const double hi = std::max({v[0][k], v[1][k], v[2][k]});
    if (lo > half[k] || hi < -half[k]) return false;
  }
  const Eigen::Vector3d edges[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  const Eigen::Vector3d normal = edges[0].cross(edges[1]);
  if (std::fabs(normal.dot(v[0])) > half.dot(normal.cwiseAbs())) return false;
  for (const Eigen::Vector3d& edge : edges) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d axis = Eigen::Vector3d::Unit(k).cross(edge);
      const double p0 = axis.dot(v[0]), p1 = axis.dot(v[1]), p2 = axis.dot(v[2]);
      const double r = half.dot(axis.cwiseAbs());
      if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
    }
  }
  return true;
}

// ---- cube split ---------------------------------------------------------------------------

// The 6 tets of the unit cube around its main diagonal (Kuhn/Freudenthal): for each
// permutation (a, b, c) of the axes, the path 0 -> e_a -> e_a + e_b -> (1,1,1). Corners are
// bit masks x | y << 1 | z << 2. The odd permutations come out negatively oriented; their
// last two corners are swapped here once, so every emitted tet is positive.
std::array<std::array<int, 4>, 6> cubeTets() {
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::array<std::array<int, 4>, 6> tets{};
  for (int p = 0; p < 6; ++p) {
    const int c1 = 1 << perms[p][0];
    const int c2 = c1 | (1 << perms[p][1]);
    tets[p] = {{0, c1, c2, 7}};
    auto corner = [](int m) { return Eigen::Vector3d(m & 1, (m >> 1) & 1, (m >> 2) & 1); };
    if (signedTetVolume(corner(0), corner(c1), corner(c2), corner(7)) < 0) std::swap(tets[p][2], tets[p][3]);
  }
  return tets;
}

Status checkSurface(const SurfaceMesh& surface, int resolution) {
  if (resolution < 1 || resolution > kMaxResolution)
    return fail(Status::InvalidArgument, "tetrahedralizeVoxels: resolution %d is outside [1, %d]", resolution,
                kMaxResolution);
  if (surface.triangles.empty() || surface.vertices.empty())
    return fail(Status::InvalidArgument, "tetrahedralizeVoxels: the surface has %zu vertices and %zu triangles",
                surface.vertices.size(), surface.triangles.size());
  for (size_t v = 0; v < surface.vertices.size(); ++v)
    if (!surface.vertices[v].allFinite())
      return fail(Status::InvalidArgument, "tetrahedralizeVoxels: surface vertex %zu has a non-finite coordinate", v);
  const int64_t n = static_cast<int64_t>(surface.vertices.size());
  for (size_t t = 0; t < surface.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (surface.triangles[t][k] < 0 || surface.triangles[t][k] >= n)
        return fail(Status::InvalidArgument, "tetrahedralizeVoxels: triangle %zu corner %d is vertex %d, outside [0, %lld)",
                    t, k, surface.triangles[t][k], static_cast<long long>(n));
  return Status::Ok;
}

Status build(const SurfaceMesh& surface, int resolution, TetMesh* out, VoxelGrid* gridOut) {
  VP_TRY(checkSurface(surface, resolution));

  // Bounding box of the vertices the triangles use.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
  for (const auto& tri : surface.triangles)
    for (int32_t v : tri) {
      lo = lo.cwiseMin(surface.vertices[v]);
      hi = hi.cwiseMax(surface.vertices[v]);
    }
  const Eigen::Vector3d extent = hi - lo;
  const double longest = extent.maxCoeff();
  if (!(longest > 0.0))
    return fail(Status::InvalidArgument, "tetrahedralizeVoxels: the surface's bounding box is a single point");

  VoxelGrid grid;
  grid.cellSize = longest / resolution;
  const double h = grid.cellSize;
  for (int k = 0; k < 3; ++k) {
    // The 1e-9 keeps an extent that is an exact multiple of h (up to round-off) from
    // getting an extra, empty layer; the grid is centred on the box, so the few 1e-9 h
    // it may then miss on each side are covered by clamping surface cells into the grid.
    const double n = std::ceil(extent[k] / h - 1e-9);
    grid.cells[k] = std::max(1, static_cast<int32_t>(std::min<double>(n, kMaxResolution)));
    grid.origin[k] = 0.5 * (lo[k] + hi[k]) - 0.5 * grid.cells[k] * h;
  }
  const int64_t nx = grid.cells[0], ny = grid.cells[1], nz = grid.cells[2];
  if (nx * ny * nz > kMaxCells)
    return fail(Status::InvalidArgument, "tetrahedralizeVoxels: resolution %d gives %lld cells, more than %lld",
                resolution, static_cast<long long>(nx * ny * nz), static_cast<long long>(kMaxCells));
  auto cellIndex = [&](int64_t i, int64_t j, int64_t k) { return (k * ny + j) * nx + i; };
  auto clampCell = [&](double coordinate, int axis) {
    const double c = std::floor((coordinate - grid.origin[axis]) / h);
    return static_cast<int64_t>(std::clamp(c, 0.0, static_cast<double>(grid.cells[axis] - 1)));
  };

  // 1. Crossings of the rays through cell centres along +x, one ray per (j, k) row.
  std::vector<Crossing> crossings;
  for (const auto& tri : surface.triangles) {
    const Eigen::Vector3d& a = surface.vertices[tri[0]];
    const Eigen::Vector3d& b = surface.vertices[tri[1]];
    const Eigen::Vector3d& c = surface.vertices[tri[2]];
    const Vec2 p[3] = {{a.y(), a.z()}, {b.y(), b.z()}, {c.y(), c.z()}};
    // Rows whose centre lies in the triangle's yz bounding box (closed on both sides).
    const double ylo = std::min({a.y(), b.y(), c.y()}), yhi = std::max({a.y(), b.y(), c.y()});
    const double zlo = std::min({a.z(), b.z(), c.z()}), zhi = std::max({a.z(), b.z(), c.z()});
    const int64_t j0 = std::max<int64_t>(0, static_cast<int64_t>(std::ceil((ylo - grid.origin.y()) / h - 0.5)));
    const int64_t j1 = std::min<int64_t>(ny - 1, static_cast<int64_t>(std::floor((yhi - grid.origin.y()) / h - 0.5)));
    const int64_t k0 = std::max<int64_t>(0, static_cast<int64_t>(std::ceil((zlo - grid.origin.z()) / h - 0.5)));
    const int64_t k1 = std::min<int64_t>(nz - 1, static_cast<int64_t>(std::floor((zhi - grid.origin.z()) / h - 0.5)));
    for (int64_t k = k0; k <= k1; ++k) {
      for (int64_t j = j0; j <= j1; ++j) {
        const Vec2 q(grid.origin.y() + (j + 0.5) * h, grid.origin.z() + (k + 0.5) * h);
        double e[3];
        const int s0 = perturbedEdgeSign(p[1], p[2], q, &e[0]);  // opposite vertex 0
        const int s1 = perturbedEdgeSign(p[2], p[0], q, &e[1]);
        const int s2 = perturbedEdgeSign(p[0], p[1], q, &e[2]);
        if (s0 == 0 || s0 != s1 || s1 != s2) continue;
        const double sum = e[0] + e[1] + e[2];
        // On a sliver the weights may be 0/0; any x within the triangle's range will do
        // for parity, the cells there are surface cells anyway.
        const double x = sum != 0.0 ? (e[0] * a.x() + e[1] * b.x() + e[2] * c.x()) / sum : (a.x() + b.x() + c.x()) / 3;
        crossings.push_back({k * ny + j, x});
      }
    }
  }
  std::sort(crossings.begin(), crossings.end());

  // 2. Cells whose centre has an odd number of crossings before it are inside.
  Array<uint8_t> kept(static_cast<size_t>(nx * ny * nz), 0);
  for (size_t begin = 0; begin < crossings.size();) {
    size_t end = begin;
    while (end < crossings.size() && crossings[end].row == crossings[begin].row) ++end;
    const int64_t row = crossings[begin].row;
    if ((end - begin) % 2 != 0)
      return fail(Status::InvalidArgument,
                  "tetrahedralizeVoxels: the surface is not closed: the ray along x at y = %g, z = %g crosses it %zu "
                  "times (an odd number)",
                  grid.origin.y() + (row % ny + 0.5) * h, grid.origin.z() + (row / ny + 0.5) * h, end - begin);
    size_t next = begin;
    for (int64_t i = 0; i < nx; ++i) {
      const double x = grid.origin.x() + (i + 0.5) * h;
      while (next < end && crossings[next].x < x) ++next;
      if ((next - begin) % 2 == 1) kept[static_cast<size_t>(row * nx + i)] = 1;
    }
    begin = end;
  }

  // 3. Cells the surface passes through. The box is grown by a relative 1e-8 so that a
  // triangle exactly on a cell face, or outside the grid by the <= 0.5e-9 h the grid may
  // miss (see above), still marks the cell despite round-off: covering the surface
  // matters more than one extra cell.
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5 * h * (1.0 + 1e-8));
  for (const auto& tri : surface.triangles) {
    const Eigen::Vector3d& a = surface.vertices[tri[0]];
    const Eigen::Vector3d& b = surface.vertices[tri[1]];
    const Eigen::Vector3d& c = surface.vertices[tri[2]];
    const Eigen::Vector3d tlo = a.cwiseMin(b).cwiseMin(c), thi = a.cwiseMax(b).cwiseMax(c);
    int64_t from[3], to[3];
    for (int ax = 0; ax < 3; ++ax) {
      from[ax] = clampCell(tlo[ax] - half[ax] * 1e-8, ax);
      to[ax] = clampCell(thi[ax] + half[ax] * 1e-8, ax);
    }
    for (int64_t k = from[2]; k <= to[2]; ++k)
      for (int64_t j = from[1]; j <= to[1]; ++j)
        for (int64_t i = from[0]; i <= to[0]; ++i) {
          uint8_t& flag = kept[static_cast<size_t>(cellIndex(i, j, k))];
          if (flag & 2) continue;
          const Eigen::Vector3d centre = grid.origin + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
          if (triangleOverlapsBox(centre, half, a, b, c)) flag |= 2;
        }
  }

  // 4. Shared lattice vertices, numbered in lattice order.
  const int64_t vx = nx + 1, vy = ny + 1, vz = nz + 1;
  auto latticeIndex = [&](int64_t i, int64_t j, int64_t k) { return (k * vy + j) * vx + i; };
  Array<int32_t> vertexOf(static_cast<size_t>(vx * vy * vz), -1);
  int64_t keptCount = 0, surfaceCount = 0;
  for (int64_t k = 0; k < nz; ++k)
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i) {
        const uint8_t flag = kept[static_cast<size_t>(cellIndex(i, j, k))];
        if (flag == 0) continue;
        ++keptCount;
        if (flag & 2) ++surfaceCount;
        for (int m = 0; m < 8; ++m)
          vertexOf[static_cast<size_t>(latticeIndex(i + (m & 1), j + ((m >> 1) & 1), k + ((m >> 2) & 1)))] = 0;
      }
  TetMesh mesh;
  for (int64_t k = 0; k < vz; ++k)
    for (int64_t j = 0; j < vy; ++j)
      for (int64_t i = 0; i < vx; ++i) {
        int32_t& v = vertexOf[static_cast<size_t>(latticeIndex(i, j, k))];
        if (v < 0) continue;
        v = static_cast<int32_t>(mesh.vertices.size());
        mesh.vertices.push_back(grid.origin + h * Eigen::Vector3d(double(i), double(j), double(k)));
      }

  // 5. Six tets per kept cube.
  static const std::array<std::array<int, 4>, 6> kCubeTets = cubeTets();
  mesh.tets.reserve(static_cast<size_t>(6 * keptCount));
  for (int64_t k = 0; k < nz; ++k)
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i) {
        if (kept[static_cast<size_t>(cellIndex(i, j, k))] == 0) continue;
        for (const auto& pattern : kCubeTets) {
          std::array<int32_t, 4> tet{};
          for (int c = 0; c < 4; ++c) {
            const int m = pattern[c];
            tet[c] = vertexOf[static_cast<size_t>(latticeIndex(i + (m & 1), j + ((m >> 1) & 1), k + ((m >> 2) & 1)))];
          }
          mesh.tets.push_back(tet);
        }
      }

  grid.keptCells = keptCount;
  grid.surfaceCells = surfaceCount;
  *out = std::move(mesh);
  if (gridOut != nullptr) *gridOut = grid;
  return Status::Ok;
}

}  // namespace

Status tetrahedralizeVoxels(const SurfaceMesh& surface, int resolution, TetMesh* out, VoxelGrid* grid) {
  if (out == nullptr) return fail(Status::InvalidArgument, "tetrahedralizeVoxels: out is null");
  try {
    return build(surface, resolution, out, grid);
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "tetrahedralizeVoxels: out of memory at resolution %d", resolution);
  }
}

}  // namespace vp
