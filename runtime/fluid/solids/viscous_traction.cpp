#include "fluid/solids/viscous_traction.h"

#include "collide/face_coverage_detail.h"
#include "geometry/closest_point_on_triangle.h"

namespace vp {
namespace {

// visit(face centre, axis, force on the body, drag per unit of the solids' velocity) for each
// face whose solid terms changed it, within the reach of `body`'s bounding box (each visit then
// decides whether the body itself is near). Serial, in the unknowns' order: the sums do not
// depend on the worker count.
template <class Visit>
void forEachExchangeNear(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                         const PreparedCollider& body, Visit&& visit) {
  const double h = grid.spec.h, reach = kReachCells * h;
  const Aabb near{body.bounds.lo - Vec3::Constant(reach), body.bounds.hi + Vec3::Constant(reach)};
  const double faceMass = density * h * h * h;
  forEachSolidExchange(grid, work, [&](int axis, const Eigen::Vector3i& f, double change, double coupling) {
    const Vec3 x = grid.faceCentre(axis, f.x(), f.y(), f.z());
    if ((x.array() < near.lo.array()).any() || (x.array() > near.hi.array()).any()) return;
    visit(x, reach, axis, Vec3((-faceMass * change / dt) * Vec3::Unit(axis)), faceMass * coupling / dt);
  });
}

}  // namespace

void addViscousTraction(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                        const PreparedCollider& surface, SurfacePressureLoad* load) {
  VertexDrag& drag = load->drag;
  if (drag.empty()) {
    drag.coefficient.assign(surface.worldVertices.size(), Vec3::Zero());
    drag.atRest.assign(surface.worldVertices.size(), Vec3::Zero());
  }
  forEachExchangeNear(grid, work, density, dt, surface, [&](const Vec3& x, double reach, int axis, const Vec3& force,
                                                             double faceDrag) {
    int triangle = -1;
    Vec3 p;
    detail::meshClosestPoint(surface, x, &triangle, &p);
    if (triangle < 0 || (p - x).norm() > reach) return;
    const Eigen::Vector3i& t = surface.triangles[static_cast<size_t>(triangle)];
    const Vec3 weights =
        barycentricWeights(p, surface.worldVertices[t[0]], surface.worldVertices[t[1]], surface.worldVertices[t[2]]);
    for (int k = 0; k < 3; ++k) {
      // The face's drag on p varies as -faceDrag times p's velocity, sum_b w_b v_b: vertex k's
      // share lumped by rows (w_k faceDrag), which keeps a translation's drag whole.
      const size_t v = static_cast<size_t>(t[k]);
      drag.coefficient[v][axis] += weights[k] * faceDrag;
      drag.atRest[v][axis] += weights[k] * (force[axis] + faceDrag * surface.vertexVelocities[v][axis]);
    }
    load->total.force += force;
    load->total.torque += p.cross(force);
  });
}

void addViscousTractionOnCollider(const MacGrid& grid, const ViscosityWorkspace& work, double density, double dt,
                                  const PreparedCollider& collider, RigidDrag* drag) {
  const Vec3& centre = collider.shape.translation;
  RigidDrag sum;
  forEachExchangeNear(grid, work, density, dt, collider,
                      [&](const Vec3& x, double reach, int axis, const Vec3& f, double faceDrag) {
                        if (!(signedDistanceBound(collider, x) <= reach)) return;
                        const Vec3 arm = (x - centre).cross(Vec3::Unit(axis));
                        sum.forceAtRest += f;
                        sum.torqueAtRest += (x - centre).cross(f);
                        sum.linear[axis] += faceDrag;
                        sum.angular += faceDrag * (arm * arm.transpose());  // symmetric to the bit
                      });
  // What the step took is the drag at the motion it saw.
  sum.forceAtRest += sum.linear.cwiseProduct(collider.shape.linearVelocity);
  sum.torqueAtRest += sum.angular * collider.shape.angularVelocity;
  *drag += sum;
}

}  // namespace vp
