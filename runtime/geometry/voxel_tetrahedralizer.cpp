#include "geometry/voxel_tetrahedralizer.h"

#include "geometry/row_parity_inside.h"
#include "geometry/surface_grid.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <utility>
#include <vector>

namespace vp {
namespace {

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

Status build(const SurfaceMesh& surface, int resolution, TetMesh* out, VoxelGrid* gridOut) {
  VoxelGrid grid;
  VP_TRY(makeSurfaceGrid(surface, resolution, "tetrahedralizeVoxels", &grid));
  const double h = grid.cellSize;
  const int64_t nx = grid.cells[0], ny = grid.cells[1], nz = grid.cells[2];
  auto cellIndex = [&](int64_t i, int64_t j, int64_t k) { return (k * ny + j) * nx + i; };
  auto clampCell = [&](double coordinate, int axis) {
    const double c = std::floor((coordinate - grid.origin[axis]) / h);
    return static_cast<int64_t>(std::clamp(c, 0.0, static_cast<double>(grid.cells[axis] - 1)));
  };

  // 1. Cells whose centre is inside (ray parity along the rows of cell centres).
  SampleGrid centres;
  centres.origin = grid.origin;
  centres.spacing = h;
  centres.offset = 0.5;
  centres.count = {{nx, ny, nz}};
  Array<uint8_t> kept;
  VP_TRY(insideByRowParity(surface, centres, "tetrahedralizeVoxels", &kept));

  // 2. Cells the surface passes through. The box is grown by a relative 1e-8 so that a
  // triangle exactly on a cell face, or outside the grid by the <= 0.5e-9 h the grid may
  // miss (surface_grid.h), still marks the cell despite round-off: covering the surface
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

  // 3. Shared lattice vertices, numbered in lattice order.
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

  // 4. Six tets per kept cube.
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
