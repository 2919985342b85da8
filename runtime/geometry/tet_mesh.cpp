#include "geometry/tet_mesh.h"

namespace vp {

double signedTetVolume(const TetMesh& mesh, size_t t) {
  const auto& tet = mesh.tets[t];
  return signedTetVolume(mesh.vertices[tet[0]], mesh.vertices[tet[1]],
                         mesh.vertices[tet[2]], mesh.vertices[tet[3]]);
}

double totalVolume(const TetMesh& mesh) {
  double sum = 0.0;
  for (size_t t = 0; t < mesh.tets.size(); ++t) sum += signedTetVolume(mesh, t);
  return sum;
}

double meanTetEdgeLength(const TetMesh& mesh) {
  if (mesh.tets.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& tet : mesh.tets) {
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        sum += (mesh.vertices[tet[i]] - mesh.vertices[tet[j]]).norm();
  }
  return sum / (6.0 * static_cast<double>(mesh.tets.size()));
}

}  // namespace vp
