// Closest point on a triangle to a point: used by the render-mesh embedding (point to tet
// faces) and by triangle-mesh colliders (unsigned distance).
#pragma once

#include <Eigen/Core>

namespace vp {

// Ericson, Real-Time Collision Detection 5.1.5: Voronoi regions of vertices, edges, face.
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

// Barycentric weights (of a, b, c) of a point q of the triangle, clamped to [0, 1] and summing
// to 1; a degenerate triangle gives the weights of its nearest vertex.
Eigen::Vector3d barycentricWeights(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c);

}  // namespace vp
