#include "fluid/solids/viscous_traction.h"

#include "collide/face_coverage_detail.h"
#include "geometry/closest_point_on_triangle.h"

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
    const Vec3 weights =
        barycentricWeights(p, surface.worldVertices[t[0]], surface.worldVertices[t[1]], surface.worldVertices[t[2]]);
    for (int k = 0; k < 3; ++k) load->vertexForces[static_cast<size_t>(t[k])] += weights[k] * force;
    load->total.force += force;
    load->total.torque += p.cross(force);
  });
}

}  // namespace vp
