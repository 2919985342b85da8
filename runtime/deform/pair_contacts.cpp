#include "deform/pair_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel_for.h"
#include "deform/deformable_contacts.h"

namespace vp {
namespace {

Vec3 nodeVector(const Array<double>& a, int32_t i) { return Vec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]); }

// Marks the nodes a self-contact query leaves out (the node and its element neighbours), so
// that each triangle visited costs three loads instead of three searches of the neighbour
// list. One per thread: the query runs inside parallel chunks; a fresh stamp per query
// forgets the last one's marks without clearing.
class NeighbourMarks {
 public:
  void mark(const ContactSurface& surface, int32_t node) {
    const size_t nodes = static_cast<size_t>(surface.nodeCount());
    if (stamp_ == std::numeric_limits<uint32_t>::max() || marks_.size() < nodes) {
      marks_.assign(std::max(marks_.size(), nodes), 0);
      stamp_ = 0;
    }
    ++stamp_;
    const ContactSurface::NodeList list = surface.neighbourList(node);
    for (const int32_t* n = list.first; n != list.last; ++n) marks_[static_cast<size_t>(*n)] = stamp_;
    marks_[static_cast<size_t>(node)] = stamp_;
  }
  bool marked(int32_t node) const { return marks_[static_cast<size_t>(node)] == stamp_; }

 private:
  std::vector<uint32_t> marks_;
  uint32_t stamp_ = 0;
};

constexpr double kOnTriangle = 1e-9;  // barycentric slack

// The point of triangle (a, b, c) under p along its normal: weights and signed height, or false
// when that point is outside the triangle or the triangle is degenerate.
bool projectOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3* weights, Vec3* normal,
                       double* height) {
  const Vec3 n = (b - a).cross(c - a);
  const double area2 = n.squaredNorm();
  if (!(area2 > 0.0)) return false;
  const Vec3 q = p - a;
  const double wb = (q.cross(c - a)).dot(n) / area2;
  const double wc = ((b - a).cross(q)).dot(n) / area2;
  const double wa = 1.0 - wb - wc;
  // A point on an edge or a corner belongs to every triangle there, whatever the rounding.
  if (wa < -kOnTriangle || wb < -kOnTriangle || wc < -kOnTriangle) return false;
  *normal = n / std::sqrt(area2);
  *height = q.dot(*normal);
  const Vec3 w = Vec3(wa, wb, wc).cwiseMax(0.0);
  *weights = w / w.sum();
  return true;
}

// The threshold below which node `node` of A touches: the rest gap, or the keep band when it
// pushed in its last step (a stiff spring at rest sits within noise of the rest gap, and a
// contact set that flips there each step feeds an oscillation).
double touchThreshold(const PairContactBody& A, int32_t node) {
  return (*A.friction)[node].lastNormalImpulse > 0.0 ? kPairContactKeep * A.rest : A.rest;
}

// Node `node` of body `a` against the triangles of body `b`: the first triangle whose
// predicted gap is below both the rest gap and `lowest` (the best so far, over the bodies
// searched before) becomes `best`, and `lowest` its gap. A triangle touched within the step
// lies within depth, or within the rest gap plus both sides' motion, of the node: B's boxes
// hold the triangles' motion (ContactSurface::refit), the query box the node's.
void nearestTriangle(const std::vector<PairContactBody>& bodies, int32_t a, int32_t node, int32_t b, double h,
                     double* lowest, PairContact* best) {
  static thread_local NeighbourMarks ownNeighbourhood;
  const PairContactBody& A = bodies[a];
  const PairContactBody& B = bodies[b];
  const Vec3 p = nodeVector(*A.x, node), vp = nodeVector(*A.v, node);
  const Vec3& nodeNormal = A.surface->nodeNormal(node);
  const double threshold = touchThreshold(A, node);
  const double reach = h * vp.norm() + A.rest + B.depth;
  const Vec3 lo = p - Vec3::Constant(reach), hi = p + Vec3::Constant(reach);
  const RefitBvh& bvh = B.surface->bvh();
  if ((lo.array() > bvh.hi().array()).any() || (hi.array() < bvh.lo().array()).any()) return;  // far off
  const Array<RefitBvh::Triangle>& triangles = B.surface->triangles();
  if (a == b) ownNeighbourhood.mark(*A.surface, node);
  bvh.visitBox(lo, hi, [&](int32_t t) {
    const RefitBvh::Triangle& tri = triangles[t];
    if (a == b && (ownNeighbourhood.marked(tri[0]) || ownNeighbourhood.marked(tri[1]) ||
                   ownNeighbourhood.marked(tri[2])))
      return;
    Vec3 w, n;
    double height;
    if (!projectOnTriangle(p, nodeVector(*B.x, tri[0]), nodeVector(*B.x, tri[1]), nodeVector(*B.x, tri[2]), &w, &n,
                           &height) || height < -B.depth)
      return;
    // A node whose surface faces the triangle's way lies beside it, not on it: a box's edge
    // node on the face round the corner, whose push would be sideways.
    if (nodeNormal.dot(n) > 0.0) return;
    std::array<Vec3, 3> vt{{nodeVector(*B.v, tri[0]), nodeVector(*B.v, tri[1]), nodeVector(*B.v, tri[2])}};
    const Vec3 vc = w[0] * vt[0] + w[1] * vt[1] + w[2] * vt[2];
    const double predicted = height + h * (vp - vc).dot(n);
    if (predicted >= threshold || predicted >= *lowest) return;
    *lowest = predicted;
    const double mt = w[0] * (*B.mass)[tri[0]] + w[1] * (*B.mass)[tri[1]] + w[2] * (*B.mass)[tri[2]];
    const double mn = (*A.mass)[node];
    best->nodeBody = a;
    best->node = node;
    best->triangleBody = b;
    best->triangleBodyId = B.id;
    best->triangleNodes = tri;
    best->weights = w;
    best->normal = n;
    best->gap = height;
    best->rest = A.rest;
    best->reducedMass = mn * mt / (mn + mt);
    best->friction = A.frictionCoefficient * B.frictionCoefficient;
    best->nodeVelocity = vp;
    best->triangleVelocities = vt;
  });
}

// Node `node` of body `a` against rigid body R (pair body `r`), as nearestTriangle: the
// contact point is the node's nearest point on R's surface, the normal the distance's gradient.
void nearestRigid(const PairContactBody& A, int32_t a, int32_t node, const RigidContactBody& R, int32_t r, double h,
                  double* lowest, PairContact* best) {
  const PreparedCollider& c = *R.geometry;
  const Vec3 p = nodeVector(*A.x, node), vp = nodeVector(*A.v, node);
  // The node's reach over the step and the rigid body's own motion (its bounds are its pose now).
  const double reach = h * vp.norm() + touchThreshold(A, node) +
                       h * (R.linearVelocity.norm() + R.angularVelocity.norm() * c.boundRadius) + 1e-9;
  if (!Aabb{p - Vec3::Constant(reach), p + Vec3::Constant(reach)}.overlaps(c.bounds)) return;
  const double phi = signedDistanceBound(c, p);
  if (phi > reach) return;
  const Vec3 n = colliderNormal(c, p);
  // The spring acts on the body at the node's own position (the body's motion carried there),
  // not at the node's nearest point on it: its tangential part then keeps the angular momentum
  // too (a contact is found within a step's reach, not only once it touches).
  const Vec3 arm = p - R.centre;
  const Vec3 vc = R.pointVelocity(arm);
  const double predicted = phi + h * (vp - vc).dot(n);
  if (predicted >= touchThreshold(A, node) || predicted >= *lowest) return;
  *lowest = predicted;
  const double mn = (*A.mass)[node];
  *best = PairContact();
  best->nodeBody = a;
  best->node = node;
  best->triangleBody = r;
  best->triangleBodyId = R.id;
  best->weights = Vec3(1.0, 0.0, 0.0);
  best->rigidSide = true;
  best->arm = arm;
  best->normal = n;
  // A node deep inside is pushed out at kMaxPushOutSpeed at most, as a collider contact is.
  best->gap = std::max(phi, A.rest - kMaxPushOutSpeed * h);
  best->rest = A.rest;
  best->reducedMass = mn * R.mass / (mn + R.mass);
  best->friction = A.frictionCoefficient * R.frictionCoefficient;
  best->nodeVelocity = vp;
  best->triangleVelocities = {{vc, Vec3::Zero(), Vec3::Zero()}};
}

}  // namespace

const RigidContactBody* findRigidBody(const std::vector<RigidContactBody>& rigids, uint32_t index1,
                                      uint32_t generation) {
  for (const RigidContactBody& r : rigids)
    if (r.id.index1 == index1 && r.id.generation == generation) return &r;
  return nullptr;
}

void findPairContacts(const std::vector<PairContactBody>& bodies, const std::vector<RigidContactBody>& rigids,
                      double h, TaskSystem& tasks, std::vector<PairContact>* out) {
  out->clear();
  // One slot per surface node of every body, filled in parallel, then read in body and node
  // order: the same contacts for any worker count.
  std::vector<int64_t> first(bodies.size() + 1, 0);
  for (size_t a = 0; a < bodies.size(); ++a) first[a + 1] = first[a] + static_cast<int64_t>(bodies[a].surfaceNodes->size());
  std::vector<PairContact> slots(static_cast<size_t>(first.back()));
  // The rigid bodies each body's surface can reach this step (its boxes hold its motion; the
  // rigid bodies' is added), so that a node visits only those.
  std::vector<std::vector<int32_t>> nearRigids(bodies.size());
  for (size_t a = 0; a < bodies.size(); ++a) {
    const PairContactBody& A = bodies[a];
    if (!A.touchesRigid) continue;
    for (size_t r = 0; r < rigids.size(); ++r) {
      const RigidContactBody& R = rigids[r];
      const double reach = kPairContactKeep * A.rest + 1e-9 +
                           h * (R.linearVelocity.norm() + R.angularVelocity.norm() * R.geometry->boundRadius);
      const Aabb surface{A.surface->bvh().lo() - Vec3::Constant(reach), A.surface->bvh().hi() + Vec3::Constant(reach)};
      if (A.filter.meets(R.filter) && surface.overlaps(R.geometry->bounds))
        nearRigids[a].push_back(static_cast<int32_t>(r));
    }
  }
  parallelFor(tasks, first.back(), 64, [&](int64_t begin, int64_t end) {
    int32_t a = static_cast<int32_t>(std::upper_bound(first.begin(), first.end(), begin) - first.begin()) - 1;
    for (int64_t s = begin; s < end; ++s) {
      while (s >= first[a + 1]) ++a;
      const PairContactBody& A = bodies[a];
      const int32_t node = (*A.surfaceNodes)[s - first[a]];
      double lowest = std::numeric_limits<double>::infinity();
      const int32_t deformables = static_cast<int32_t>(bodies.size());
      for (int32_t b = 0; b < deformables; ++b)
        if (b == a ? A.selfCollision : A.filter.meets(bodies[b].filter))
          nearestTriangle(bodies, a, node, b, h, &lowest, &slots[static_cast<size_t>(s)]);
      for (int32_t r : nearRigids[static_cast<size_t>(a)])
        nearestRigid(A, a, node, rigids[static_cast<size_t>(r)], deformables + r, h, &lowest,
                     &slots[static_cast<size_t>(s)]);
    }
  });
  for (PairContact& c : slots) {
    if (c.node < 0) continue;
    const PairFriction& f = (*bodies[c.nodeBody].friction)[c.node];
    if (f.other == c.triangleBodyId) {
      c.state = f;
      c.state.stick -= c.state.stick.dot(c.normal) * c.normal;
    } else {
      // A node that arrives slipping slides (with no friction until it has a normal impulse)
      // and sticks once the slip stops: a fresh stick spring would stop its slip within the
      // step, whatever Coulomb's cone allows. Without friction nothing sticks.
      c.state.sliding = c.friction <= 0.0 || c.startSlip().norm() >= kPairArrivingSlipSpeed ? 1 : 0;
    }
    out->push_back(c);
  }
}

}  // namespace vp
