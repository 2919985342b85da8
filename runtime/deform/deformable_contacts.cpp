#include "deform/deformable_contacts.h"

#include <algorithm>
#include <cmath>

namespace vp {

// Central differences of the signed distance: works for every shape the exact geometry
// supports, and the step is far below any feature size we simulate.
Vec3 colliderNormal(const PreparedCollider& c, const Vec3& x) {
  const double eps = 1e-6 * (1.0 + x.cwiseAbs().maxCoeff());
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    Vec3 a = x, b = x;
    a[k] += eps;
    b[k] -= eps;
    g[k] = (signedDistanceBound(c, a) - signedDistanceBound(c, b)) / (2.0 * eps);
  }
  const double n = g.norm();
  return n > 1e-12 ? Vec3(g / n) : Vec3::UnitY();
}

void findNodeContacts(const Array<double>& x, const Array<double>& v, const Array<int32_t>& surfaceNodes,
                      const std::vector<ContactCollider>& colliders, double h, double bodyFriction, double margin,
                      Array<NodeContact>* out) {
  out->clear();
  if (colliders.empty()) return;
  for (int32_t node : surfaceNodes) {
    const Vec3 p(x[3 * node], x[3 * node + 1], x[3 * node + 2]);
    const Vec3 vel(v[3 * node], v[3 * node + 1], v[3 * node + 2]);
    const double reach = h * vel.norm() + margin;
    NodeContact best;
    double bestPredicted = 0.0;
    for (const ContactCollider& cc : colliders) {
      const PreparedCollider& c = *cc.geometry;
      // Cheap reject: the node cannot reach the collider's bounds this step. Colliders move
      // too; their own motion per step is added through the bound's slack below.
      const Vec3 slack = Vec3::Constant(reach + h * c.shape.linearVelocity.norm() + 1e-9);
      if (((p + slack) - c.bounds.lo).minCoeff() < 0.0 || (c.bounds.hi - (p - slack)).minCoeff() < 0.0) continue;
      const double phi = signedDistanceBound(c, p);
      if (phi > reach + h * (c.shape.linearVelocity.norm() + c.shape.angularVelocity.norm() * c.boundRadius))
        continue;
      const Vec3 n = colliderNormal(c, p);
      const Vec3 vc = c.shape.linearVelocity + c.shape.angularVelocity.cross(p - c.translation);
      const double predicted = phi + h * (vel - vc).dot(n);
      if (predicted >= margin || (best.node >= 0 && predicted >= bestPredicted)) continue;
      best.node = node;
      best.normal = n;
      best.colliderVelocity = vc;
      best.normalSpeed = vc.dot(n) + std::min(-phi / h, kMaxPushOutSpeed);
      best.friction = bodyFriction * cc.friction;
      best.colliderIndex1 = cc.index1;
      best.colliderGeneration = cc.generation;
      bestPredicted = predicted;
    }
    if (best.node >= 0) out->push_back(best);
  }
}

}  // namespace vp
