#include "geometry/segment_surface_crossing.h"

#include <algorithm>

namespace vp {
namespace {

constexpr double kSlack = 1e-9;

// Moeller-Trumbore: the segment parameter where a + t d meets triangle (p0, p1, p2), if it does
// within the slack; false for a segment parallel to the triangle's plane.
bool segmentMeetsTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& d, const Eigen::Vector3d& p0,
                          const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, double* t) {
  const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
  const Eigen::Vector3d pv = d.cross(e2);
  const double det = e1.dot(pv);
  if (det == 0.0) return false;
  const Eigen::Vector3d s = a - p0;
  const double u = s.dot(pv) / det;
  const Eigen::Vector3d qv = s.cross(e1);
  const double v = d.dot(qv) / det;
  const double hit = e2.dot(qv) / det;
  if (!(u >= -kSlack && v >= -kSlack && u + v <= 1.0 + kSlack && hit >= -kSlack && hit <= 1.0 + kSlack)) return false;
  *t = std::clamp(hit, 0.0, 1.0);
  return true;
}

}  // namespace

bool firstSurfaceCrossing(const RefitBvh& bvh, const SurfaceMesh& surface, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& b, double* t) {
  const Eigen::Vector3d d = b - a;
  double best = 2.0;
  bvh.visitRay(a, d, 1.0, [&](int32_t triangle, double limit) {
    const auto& tri = surface.triangles[static_cast<size_t>(triangle)];
    double hit;
    if (segmentMeetsTriangle(a, d, surface.vertices[tri[0]], surface.vertices[tri[1]], surface.vertices[tri[2]], &hit))
      best = std::min(best, hit);
    return std::min(limit, best + kSlack);  // farther triangles cannot give a smaller t
  });
  if (best > 1.0) return false;
  *t = best;
  return true;
}

}  // namespace vp
