#include "beam_mesh.h"

#include <array>
#include <cmath>
#include <sstream>

namespace vp::bench {

BeamMesh makeBeamMesh(int cellsX, int cellsY, int cellsZ, double lengthX, double sizeY, double sizeZ) {
  BeamMesh mesh;
  if (cellsX < 1 || cellsY < 1 || cellsZ < 1) return mesh;
  const int pointsX = cellsX + 1, pointsY = cellsY + 1, pointsZ = cellsZ + 1;
  // X is the slowest index so the clamped face (i == 0) is one contiguous block of vertices.
  auto vertexIndex = [&](int i, int j, int k) { return static_cast<int32_t>((i * pointsY + j) * pointsZ + k); };

  mesh.vertices.reserve(size_t(3) * pointsX * pointsY * pointsZ);
  for (int i = 0; i < pointsX; ++i)
    for (int j = 0; j < pointsY; ++j)
      for (int k = 0; k < pointsZ; ++k) {
        // Multiply before dividing so the end faces land exactly on 0 and the given sizes.
        mesh.vertices.push_back(lengthX * i / cellsX);
        mesh.vertices.push_back(sizeY * j / cellsY);
        mesh.vertices.push_back(sizeZ * k / cellsZ);
        if (i == 0) mesh.fixedVertices.push_back(vertexIndex(i, j, k));
      }
  mesh.tipVertex = vertexIndex(cellsX, cellsY / 2, cellsZ / 2);

  // The six tets of a cube are the monotone paths from corner 000 to corner 111: one per order
  // (a, b, c) in which the axes are stepped. The tet (000, e_a, e_a + e_b, 111) has the sign of
  // det[e_a, e_b, e_c], i.e. of the permutation, so odd orders swap their last two corners.
  struct AxisOrder {
    std::array<int, 3> axes;
    bool odd;
  };
  const std::array<AxisOrder, 6> orders = {{{{0, 1, 2}, false},
                                            {{1, 2, 0}, false},
                                            {{2, 0, 1}, false},
                                            {{0, 2, 1}, true},
                                            {{1, 0, 2}, true},
                                            {{2, 1, 0}, true}}};
  mesh.tets.reserve(size_t(24) * cellsX * cellsY * cellsZ);
  for (int i = 0; i < cellsX; ++i)
    for (int j = 0; j < cellsY; ++j)
      for (int k = 0; k < cellsZ; ++k)
        for (const AxisOrder& order : orders) {
          std::array<int, 3> corner = {i, j, k};
          std::array<int32_t, 4> tet{};
          tet[0] = vertexIndex(corner[0], corner[1], corner[2]);
          for (int step = 0; step < 3; ++step) {
            ++corner[order.axes[step]];
            tet[step + 1] = vertexIndex(corner[0], corner[1], corner[2]);
          }
          if (order.odd) std::swap(tet[2], tet[3]);
          mesh.tets.insert(mesh.tets.end(), tet.begin(), tet.end());
        }
  return mesh;
}

bool beamCellsForTetCount(int64_t tetCount, BeamCells* cells) {
  if (tetCount <= 0 || tetCount % 24 != 0) return false;
  const int64_t cubeOfN = tetCount / 24;
  const auto n = static_cast<int64_t>(std::llround(std::cbrt(double(cubeOfN))));
  if (n < 1 || n * n * n != cubeOfN) return false;
  cells->x = static_cast<int>(4 * n);
  cells->y = static_cast<int>(n);
  cells->z = static_cast<int>(n);
  return true;
}

double signedTetVolume(const BeamMesh& mesh, int32_t tet) {
  const double* p[4];
  for (int c = 0; c < 4; ++c) p[c] = &mesh.vertices[size_t(3) * mesh.tets[size_t(4) * tet + c]];
  double e[3][3];
  for (int c = 0; c < 3; ++c)
    for (int d = 0; d < 3; ++d) e[c][d] = p[c + 1][d] - p[0][d];
  const double tripleProduct = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                               e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                               e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return tripleProduct / 6.0;
}

std::string findBeamMeshDefect(const BeamMesh& mesh, double expectedVolume) {
  std::ostringstream why;
  if (mesh.tets.empty() || mesh.tets.size() % 4 != 0) {
    why << "beam mesh has no tets or a partial tet";
    return why.str();
  }
  if (mesh.tipVertex < 0 || mesh.tipVertex >= mesh.vertexCount() || mesh.fixedVertices.empty()) {
    why << "beam mesh lacks a tip vertex or fixed vertices";
    return why.str();
  }
  double totalVolume = 0;
  for (int32_t t = 0; t < mesh.tetCount(); ++t) {
    for (int c = 0; c < 4; ++c) {
      const int32_t v = mesh.tets[size_t(4) * t + c];
      if (v < 0 || v >= mesh.vertexCount()) {
        why << "tet " << t << " names vertex " << v << " of " << mesh.vertexCount();
        return why.str();
      }
    }
    const double volume = signedTetVolume(mesh, t);
    if (!(volume > 0)) {
      why << "tet " << t << " has volume " << volume << " (not positively oriented)";
      return why.str();
    }
    totalVolume += volume;
  }
  if (std::abs(totalVolume - expectedVolume) > 1e-9 * std::abs(expectedVolume)) {
    why << "tet volumes sum to " << totalVolume << ", expected " << expectedVolume;
    return why.str();
  }
  return {};
}

}  // namespace vp::bench
