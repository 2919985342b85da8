// Closest point on a triangle to a point: used by the render-mesh embedding (point to tet
// faces) and by triangle-mesh colliders (unsigned distance).
#pragma once

#include <Eigen/Core>

namespace vp {

// Ericson, Real-Time Collision Detection 5.1.5: Voronoi regions of vertices, edges, face.
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

}  // namespace vp
