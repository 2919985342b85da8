#include "fluid/solids/viscous_traction.h"

#include "collide/face_coverage_detail.h"
#include "geometry/closest_point_on_triangle.h"

namespace vp {
namespace {

// visit(face centre, force on the body) for each face whose solid terms changed it, within the
// reach of `body`'s bounding box (each visit then decides whether the body itself is near).
// Serial, in the unknowns' order: the sums do not depend on the worker count.
template <class Visit>
void forEachExchangeNear(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                         const PreparedCollider& body, Visit&& visit) {
  const double h = grid.spec.h, reach = kReachCells * h;
  const Aabb near{body.bounds.lo - Vec3::Constant(reach), body.bounds.hi + Vec3::Constant(reach)};
  const double faceMass = density * h * h * h;
  forEachSolidExchange(grid, work, [&](int axis, const Eigen::Vector3i& f, double change) {
    const Vec3 x = grid.faceCentre(axis, f.x(), f.y(), f.z());
    if ((x.array() < near.lo.array()).any() || (x.array() > near.hi.array()).any()) return;
    visit(x, reach, Vec3((-faceMass * change / dt) * Vec3::Unit(axis)));
  });
}

}  // namespace

void addViscousTraction(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                        const PreparedCollider& surface, SurfacePressureLoad* load) {
  forEachExchangeNear(grid, work, density, dt, surface, [&](const Vec3& x, double reach, const Vec3& force) {
    int triangle = -1;
    Vec3 p;
    detail::meshClosestPoint(surface, x, &triangle, &p);
    if (triangle < 0 || (p - x).norm() > reach) return;
    const Eigen::Vector3i& t = surface.triangles[static_cast<size_t>(triangle)];
    const Vec3 weights =
        barycentricWeights(p, surface.worldVertices[t[0]], surface.worldVertices[t[1]], surface.worldVertices[t[2]]);
    for (int k = 0; k < 3; ++k) load->vertexForces[static_cast<size_t>(t[k])] += weights[k] * force;
    load->total.force += force;
    load->total.torque += p.cross(force);
  });
}

void addViscousTractionOnCollider(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                                  const PreparedCollider& collider, const Vec3& centre, PressureLoad* load) {
  forEachExchangeNear(grid, work, density, dt, collider, [&](const Vec3& x, double reach, const Vec3& force) {
    if (!(signedDistanceBound(collider, x) <= reach)) return;
    load->force += force;
    load->torque += (x - centre).cross(force);
  });
}

}  // namespace vp
