#include "fluid/solids/viscous_traction.h"

#include "collide/face_coverage_detail.h"

namespace vp {

void addViscousTraction(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                        const PreparedCollider& surface, SurfacePressureLoad* load) {
  const double h = grid.spec.h, reach = kReachCells * h;
  const Aabb near{surface.bounds.lo - Vec3::Constant(reach), surface.bounds.hi + Vec3::Constant(reach)};
  const double faceMass = density * h * h * h;
  // Serial, in the unknowns' order: the sums do not depend on the worker count.
  forEachSolidExchange(grid, work, [&](int axis, const Eigen::Vector3i& f, double change) {
    const Vec3 x = grid.faceCentre(axis, f.x(), f.y(), f.z());
    if ((x.array() < near.lo.array()).any() || (x.array() > near.hi.array()).any()) return;
    int triangle = -1;
    Vec3 p;
    detail::meshClosestPoint(surface, x, &triangle, &p);
    if (triangle < 0 || (p - x).norm() > reach) return;
    const Vec3 force = (-faceMass * change / dt) * Vec3::Unit(axis);
    const Eigen::Vector3i& t = surface.triangles[static_cast<size_t>(triangle)];
    const Vec3 &a = surface.worldVertices[t[0]], &b = surface.worldVertices[t[1]], &c = surface.worldVertices[t[2]];
    // Barycentric weights of p in the triangle (p lies on it).
    const Vec3 n = (b - a).cross(c - a);
    const double area2 = n.squaredNorm();
    Vec3 weights(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
    if (area2 > 0.0) {
      weights[1] = (p - a).cross(c - a).dot(n) / area2;
      weights[2] = (b - a).cross(p - a).dot(n) / area2;
      weights[0] = 1.0 - weights[1] - weights[2];
    }
    for (int k = 0; k < 3; ++k) load->vertexForces[static_cast<size_t>(t[k])] += weights[k] * force;
    load->total.force += force;
    load->total.torque += p.cross(force);
  });
}

}  // namespace vp
