#include "beam_mesh.h"

#include "geometry/box_tet_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace vp::bench {

BeamMesh makeBeamMesh(int cellsX, int cellsY, int cellsZ, double lengthX, double sizeY, double sizeZ) {
  BeamMesh mesh;
  if (cellsX < 1 || cellsY < 1 || cellsZ < 1) return mesh;
  // The runtime's box mesher (same Kuhn split the voxel tetrahedralizer and scenes use).
  const TetMesh box = makeBoxTetMesh({cellsX, cellsY, cellsZ}, Vec3(lengthX, sizeY, sizeZ), Vec3::Zero());
  for (const Vec3& v : box.vertices) mesh.vertices.insert(mesh.vertices.end(), {v.x(), v.y(), v.z()});
  for (const auto& t : box.tets) mesh.tets.insert(mesh.tets.end(), t.begin(), t.end());
  for (int32_t i = 0; i < static_cast<int32_t>(box.vertices.size()); ++i)
    if (box.vertices[i].x() == 0.0) mesh.fixedVertices.push_back(i);
  // Lattice order is x fastest: vertex (i, j, k) = i + (cx + 1) (j + (cy + 1) k).
  mesh.tipVertex = cellsX + (cellsX + 1) * (cellsY / 2 + (cellsY + 1) * (cellsZ / 2));
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

TetMesh toTetMesh(const BeamMesh& beam) {
  TetMesh mesh;
  for (int32_t i = 0; i < beam.vertexCount(); ++i)
    mesh.vertices.emplace_back(beam.vertices[3 * i], beam.vertices[3 * i + 1], beam.vertices[3 * i + 2]);
  for (int32_t t = 0; t < beam.tetCount(); ++t)
    mesh.tets.push_back({beam.tets[4 * t], beam.tets[4 * t + 1], beam.tets[4 * t + 2], beam.tets[4 * t + 3]});
  return mesh;
}

bool beamCellsNearTetCount(int64_t tetCount, BeamCells* cells) {
  if (tetCount < 24) return false;
  if (beamCellsForTetCount(tetCount, cells)) return true;
  const auto n = std::max<int64_t>(1, std::llround(std::cbrt(double(tetCount) / 24.0)));
  cells->x = static_cast<int>(std::max<int64_t>(1, std::llround(double(tetCount) / double(6 * n * n))));
  cells->y = static_cast<int>(n);
  cells->z = static_cast<int>(n);
  return true;
}

double signedTetVolume(const BeamMesh& mesh, int32_t tet) {
  Vec3 p[4];
  for (int c = 0; c < 4; ++c) p[c] = Eigen::Map<const Vec3>(&mesh.vertices[size_t(3) * mesh.tets[size_t(4) * tet + c]]);
  return vp::signedTetVolume(p[0], p[1], p[2], p[3]);
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
