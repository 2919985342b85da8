#include "geometry/mesh_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vp {
namespace {

constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};

// The angle at edge (a, b) between the directions to c and d, both taken across the edge.
double dihedralDegrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d) {
  const Eigen::Vector3d e = (b - a).normalized();
  Eigen::Vector3d u = c - a, v = d - a;
  u -= u.dot(e) * e;
  v -= v.dot(e) * e;
  const double cosine = std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0);
  return std::acos(cosine) * 180.0 / M_PI;
}

}  // namespace

void tetDihedralRangeDegrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                             const Eigen::Vector3d& d, double* minDegrees, double* maxDegrees) {
  const Eigen::Vector3d* p[4] = {&a, &b, &c, &d};
  *minDegrees = std::numeric_limits<double>::infinity();
  *maxDegrees = 0.0;
  for (const auto& edge : kEdges) {
    const double angle = dihedralDegrees(*p[edge[0]], *p[edge[1]], *p[edge[2]], *p[edge[3]]);
    *minDegrees = std::min(*minDegrees, angle);
    *maxDegrees = std::max(*maxDegrees, angle);
  }
}

double enclosedVolume(const SurfaceMesh& surface) {
  double volume = 0.0;
  for (const auto& t : surface.triangles)
    volume += surface.vertices[t[0]].dot(surface.vertices[t[1]].cross(surface.vertices[t[2]])) / 6.0;
  return volume;
}

TetMeshQuality tetMeshQuality(const TetMesh& mesh, const SurfaceMesh& surface) {
  TetMeshQuality q;
  q.minDihedralDegrees = std::numeric_limits<double>::infinity();
  q.maxDihedralDegrees = 0.0;
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    double lo, hi;
    tetDihedralRangeDegrees(mesh.vertices[tet[0]], mesh.vertices[tet[1]], mesh.vertices[tet[2]],
                            mesh.vertices[tet[3]], &lo, &hi);
    q.minDihedralDegrees = std::min(q.minDihedralDegrees, lo);
    q.maxDihedralDegrees = std::max(q.maxDihedralDegrees, hi);
  }
  if (mesh.tets.empty()) q.minDihedralDegrees = 0.0;
  q.tetVolume = totalVolume(mesh);
  q.surfaceVolume = enclosedVolume(surface);
  return q;
}

}  // namespace vp
