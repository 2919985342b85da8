#include "geometry/box_tet_mesh.h"

#include <utility>

#include "core/physical_limits.h"

namespace vp {

Status checkBoxTetMeshArgs(const std::array<int, 3>& cells, const Vec3& size) {
  for (int k = 0; k < 3; ++k)
    if (cells[k] < 1 || cells[k] > kMaxBoxCellsPerAxis)
      return fail(Status::InvalidArgument, "cells[%d] = %d: must be in [1, %d]", k, cells[k], kMaxBoxCellsPerAxis);
  const int64_t total = int64_t(cells[0]) * cells[1] * cells[2];
  if (total > kMaxBoxCells)
    return fail(Status::InvalidArgument, "cells = (%d, %d, %d): %lld cells, at most %lld", cells[0], cells[1], cells[2],
                static_cast<long long>(total), static_cast<long long>(kMaxBoxCells));
  static const char* const kSizeFields[3] = {"size.x", "size.y", "size.z"};
  for (int k = 0; k < 3; ++k) VP_TRY(checkLength(kSizeFields[k], size[k]));
  return Status::Ok;
}

TetMesh makeBoxTetMesh(const std::array<int, 3>& cells, const Vec3& size, const Vec3& minCorner) {
  TetMesh mesh;
  const int nx = cells[0] + 1, ny = cells[1] + 1, nz = cells[2] + 1;
  auto vertex = [&](int i, int j, int k) { return static_cast<int32_t>(i + nx * (j + ny * k)); };
  mesh.vertices.reserve(static_cast<size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.vertices.push_back(minCorner + Vec3(size.x() * i / cells[0], size.y() * j / cells[1],
                                                 size.z() * k / cells[2]));
  // The 6 monotone paths from corner 000 to 111, one tet each.
  static const int kAxisOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  mesh.tets.reserve(static_cast<size_t>(6) * cells[0] * cells[1] * cells[2]);
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i)
        for (const auto& order : kAxisOrders) {
          int c[3] = {i, j, k};
          std::array<int32_t, 4> tet;
          tet[0] = vertex(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            c[order[s]]++;
            tet[s + 1] = vertex(c[0], c[1], c[2]);
          }
          if (signedTetVolume(mesh.vertices[tet[0]], mesh.vertices[tet[1]], mesh.vertices[tet[2]],
                              mesh.vertices[tet[3]]) < 0)
            std::swap(tet[2], tet[3]);
          mesh.tets.push_back(tet);
        }
  return mesh;
}

}  // namespace vp
