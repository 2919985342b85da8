// Face coverage by convex polyhedra given as half-spaces: half-space plane, box, convex hull.
//
// Exact: the solid's cross-section with the face plane is the intersection of the half-planes
// { n[a1] u + n[a2] v <= d - n[a] c0 }; clipping the face square by each of them
// (Sutherland-Hodgman) leaves exactly (square ∩ cross-section), whose area is the shoelace sum.
// A half-space whose normal is parallel to the face normal keeps all or nothing of the face.
#include "collide/face_coverage_detail.h"

namespace vp {
namespace detail {

double coveredAreaHalfSpaces(const Eigen::Vector4d* planes, int count, const FaceFrame& fr) {
  FixedPolygon<kMaxConvexPlanes + 4> poly;
  poly.setRect(fr.u0, fr.v0, fr.u1, fr.v1);
  return clipByHalfSpaces(poly, planes, count, fr) ? poly.area() : 0.0;
}

}  // namespace detail
}  // namespace vp
