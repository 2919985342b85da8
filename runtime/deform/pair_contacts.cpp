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

// A point that may touch a body's triangles within a step: where it is and how fast it moves,
// the way its own surface faces (a triangle facing that way too lies beside it, not under it:
// a box's edge node on the face round the corner, whose push would be sideways), its contact
// margin and the gap below which it touches.
struct TouchQuery {
  Vec3 p, v, facing;
  double rest, threshold;
};

// visit(triangle, weights, normal, height, triangle velocities) for each triangle of B that the
// point touches within the step h with a predicted gap below both its threshold and *lowest
// (the best so far, over the bodies searched before), which then becomes that gap; skip(tri)
// leaves a triangle out. A triangle touched within the step lies within depth, or within the
// margin plus both sides' motion, of the point: B's boxes hold the triangles' motion
// (ContactSurface::refit), the query box the point's.
template <class Skip, class Visit>
void touchingTriangles(const TouchQuery& q, const PairContactBody& B, double h, double* lowest, const Skip& skip,
                       const Visit& visit) {
  const double reach = h * (q.v - B.surface->frameVelocity()).norm() + q.rest + B.depth;
  const Vec3 lo = q.p - Vec3::Constant(reach), hi = q.p + Vec3::Constant(reach);
  const RefitBvh& bvh = B.surface->bvh();
  if ((lo.array() > bvh.hi().array()).any() || (hi.array() < bvh.lo().array()).any()) return;  // far off
  const Array<RefitBvh::Triangle>& triangles = B.surface->triangles();
  bvh.visitBox(lo, hi, [&](int32_t t) {
    const RefitBvh::Triangle& tri = triangles[t];
    if (skip(tri)) return;
    Vec3 w, n;
    double height;
    if (!projectOnTriangle(q.p, nodeVector(*B.x, tri[0]), nodeVector(*B.x, tri[1]), nodeVector(*B.x, tri[2]), &w, &n,
                           &height) || height < -B.depth)
      return;
    if (q.facing.dot(n) > 0.0) return;
    const std::array<Vec3, 3> vt{{nodeVector(*B.v, tri[0]), nodeVector(*B.v, tri[1]), nodeVector(*B.v, tri[2])}};
    const Vec3 vc = w[0] * vt[0] + w[1] * vt[1] + w[2] * vt[2];
    const double predicted = height + h * (q.v - vc).dot(n);
    if (predicted >= q.threshold || predicted >= *lowest) return;
    *lowest = predicted;
    visit(tri, w, n, height, vt);
  });
}

// The mass of the triangle's point with weights w.
double pointMass(const PairContactBody& B, const RefitBvh::Triangle& tri, const Vec3& w) {
  return w[0] * (*B.mass)[tri[0]] + w[1] * (*B.mass)[tri[1]] + w[2] * (*B.mass)[tri[2]];
}

// The triangle side of a contact with triangle `tri` of body b (B).
void setTriangleSide(const PairContactBody& B, int32_t b, const RefitBvh::Triangle& tri, const Vec3& w, const Vec3& n,
                     const std::array<Vec3, 3>& vt, PairContact* c) {
  c->triangleBody = b;
  c->triangleBodyId = B.id;
  c->triangleNodes = tri;
  c->weights = w;
  c->normal = n;
  c->triangleVelocities = vt;
}

// Node `node` of body `a` against the triangles of body `b`: the first triangle whose
// predicted gap is below both the node's threshold and `lowest` becomes `best`.
void nearestTriangle(const std::vector<PairContactBody>& bodies, int32_t a, int32_t node, int32_t b, double h,
                     double* lowest, PairContact* best) {
  static thread_local NeighbourMarks ownNeighbourhood;
  const PairContactBody& A = bodies[a];
  const PairContactBody& B = bodies[b];
  const TouchQuery q{nodeVector(*A.x, node), nodeVector(*A.v, node), A.surface->nodeNormal(node), A.rest,
                     touchThreshold(A, node)};
  if (a == b) ownNeighbourhood.mark(*A.surface, node);
  auto ownNeighbour = [&](const RefitBvh::Triangle& tri) {
    return a == b && (ownNeighbourhood.marked(tri[0]) || ownNeighbourhood.marked(tri[1]) ||
                      ownNeighbourhood.marked(tri[2]));
  };
  touchingTriangles(q, B, h, lowest, ownNeighbour,
                    [&](const RefitBvh::Triangle& tri, const Vec3& w, const Vec3& n, double height,
                        const std::array<Vec3, 3>& vt) {
                      const double mt = pointMass(B, tri, w), mn = (*A.mass)[node];
                      best->nodeBody = a;
                      best->node = node;
                      setTriangleSide(B, b, tri, w, n, vt, best);
                      best->gap = height;
                      best->rest = A.rest;
                      best->reducedMass = mn * mt / (mn + mt);
                      best->friction = A.frictionCoefficient * B.frictionCoefficient;
                      best->nodeVelocity = q.v;
                    });
}

// The friction state B keeps for corner `corner` of rigid body `rigid`, or null.
const CornerFriction* cornerState(const PairContactBody& B, const PairBodyId& rigid, int32_t corner) {
  for (const CornerFriction& f : *B.cornerFriction)
    if (f.rigid == rigid && f.corner == corner) return &f;
  return nullptr;
}

// Corner `corner` (at q) of rigid body R (pair body r) against the triangles of body `b` that
// skip(tri) leaves in, as nearestTriangle: its arm's direction is the way the corner faces, B's
// margin its own (and its keep band when it pushed in its last step).
template <class Skip = bool (*)(const RefitBvh::Triangle&)>
void nearestTriangleToCorner(const RigidContactBody& R, int32_t r, int32_t corner, const Vec3& q,
                             const std::vector<PairContactBody>& bodies, int32_t b, double h, double* lowest,
                             PairContact* best, const Skip& skip = [](const RefitBvh::Triangle&) { return false; }) {
  const PairContactBody& B = bodies[b];
  const Vec3 arm = q - R.centre;
  const CornerFriction* last = cornerState(B, R.id, corner);
  const double threshold = last != nullptr && last->state.lastNormalImpulse > 0.0 ? kPairContactKeep * B.rest : B.rest;
  const TouchQuery query{q, R.pointVelocity(arm), arm, B.rest, threshold};
  touchingTriangles(query, B, h, lowest, skip,
                    [&](const RefitBvh::Triangle& tri, const Vec3& w, const Vec3& n, double height,
                        const std::array<Vec3, 3>& vt) {
                      const double mt = pointMass(B, tri, w);
                      *best = PairContact();
                      best->nodeBody = r;
                      best->node = corner;
                      best->rigidNode = true;
                      best->nodeBodyId = R.id;
                      best->arm = arm;
                      setTriangleSide(B, b, tri, w, n, vt, best);
                      // Deep inside, it is pushed out at kMaxPushOutSpeed at most, as a node in a collider.
                      best->gap = std::max(height, B.rest - kMaxPushOutSpeed * h);
                      best->rest = B.rest;
                      best->reducedMass = R.mass * mt / (R.mass + mt);
                      best->friction = R.frictionCoefficient * B.frictionCoefficient;
                      best->nodeVelocity = query.v;
                    });
}

// Node `node` of body `a` against rigid body R (pair body `r`), as nearestTriangle: the
// contact point is the node's nearest point on R's surface, the normal the distance's gradient.
void nearestRigid(const PairContactBody& A, int32_t a, int32_t node, const RigidContactBody& R, int32_t r, double h,
                  double* lowest, PairContact* best) {
  const PreparedCollider& c = *R.geometry;
  const Vec3 p = nodeVector(*A.x, node), vp = nodeVector(*A.v, node);
  // The node's reach over the step and the rigid body's own motion (its bounds are its pose now).
  const double reach = h * vp.norm() + touchThreshold(A, node) + R.sweep(h, Vec3::Zero()) + 1e-9;
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

// A sphere, capsule or cylinder: no corners.
bool isRound(const PreparedCollider& shape) {
  const ShapeKind k = shape.shape.kind;
  return k == ShapeKind::Sphere || k == ShapeKind::Capsule || k == ShapeKind::Cylinder;
}

// A round shape's point farthest along unit d (its support point), world frame: a sphere's,
// a capsule's and a cylinder's (local y axis, halfHeight).
Vec3 roundSupport(const PreparedCollider& shape, const Vec3& d) {
  const ColliderShape& s = shape.shape;
  const Vec3 axis = shape.rotation.col(1);
  const double along = d.dot(axis);
  const Vec3 end = s.kind == ShapeKind::Sphere ? Vec3::Zero() : Vec3((along >= 0.0 ? 1.0 : -1.0) * s.halfHeight * axis);
  Vec3 radial = d;
  if (s.kind == ShapeKind::Cylinder) {
    radial = d - along * axis;  // the rim's point: across the axis only
    const double n = radial.norm();
    radial = n > 1e-12 ? Vec3(radial / n) : Vec3::Zero();
  }
  return shape.translation + end + s.radius * radial;
}

// A round body R (pair body r) against the triangles of body `b`: each triangle near it
// against the body's point deepest under the triangle's plane (its support point along the
// inward normal), tested against that triangle alone, as nearestTriangleToCorner tests a
// corner. Such a point is not one of a fixed set: its friction state is keyed by the
// triangle's index. Appends the contacts in the BVH's order.
void roundContacts(const RigidContactBody& R, int32_t r, const std::vector<PairContactBody>& bodies, int32_t b,
                   double h, std::vector<PairContact>* out) {
  const PairContactBody& B = bodies[b];
  const double reach = B.rest + B.depth + R.sweep(h, B.surface->frameVelocity());
  const Aabb near{R.geometry->bounds.lo - Vec3::Constant(reach), R.geometry->bounds.hi + Vec3::Constant(reach)};
  const Array<RefitBvh::Triangle>& triangles = B.surface->triangles();
  B.surface->bvh().visitBox(near.lo, near.hi, [&](int32_t t) {
    const RefitBvh::Triangle& tri = triangles[t];
    const Vec3 a = nodeVector(*B.x, tri[0]);
    const Vec3 n = (nodeVector(*B.x, tri[1]) - a).cross(nodeVector(*B.x, tri[2]) - a);
    if (!(n.squaredNorm() > 0.0)) return;
    double lowest = std::numeric_limits<double>::infinity();
    PairContact contact;
    nearestTriangleToCorner(R, r, t, roundSupport(*R.geometry, Vec3(-n.normalized())), bodies, b, h, &lowest,
                            &contact, [&](const RefitBvh::Triangle& other) { return other != tri; });
    if (contact.node >= 0) out->push_back(contact);
  });
}

// Appends one slot per corner of every rigid body that some body with touchesRigid set can
// reach this step (its boxes hold its motion; the rigid body's is added), filled in parallel
// with the corner's nearest touching triangle over those bodies; in rigid body, corner order.
void findCornerContacts(const std::vector<PairContactBody>& bodies, const std::vector<RigidContactBody>& rigids,
                        double h, TaskSystem& tasks, std::vector<PairContact>* slots) {
  struct Corner {
    int32_t rigid, index;
    Vec3 position;
  };
  std::vector<Corner> corners;
  std::vector<std::vector<int32_t>> nearBodies(rigids.size());
  std::vector<int32_t> roundBodies;  // their points come from the triangles (roundContacts)
  Array<Vec3> vertices;
  for (size_t r = 0; r < rigids.size(); ++r) {
    const RigidContactBody& R = rigids[r];
    for (size_t b = 0; b < bodies.size(); ++b) {
      const PairContactBody& B = bodies[b];
      const double reach = B.rest + B.depth + 1e-9 + R.sweep(h, B.surface->frameVelocity());
      const Aabb surface{B.surface->bvh().lo() - Vec3::Constant(reach), B.surface->bvh().hi() + Vec3::Constant(reach)};
      if (B.touchesRigid && B.filter.meets(R.filter) && surface.overlaps(R.geometry->bounds))
        nearBodies[r].push_back(static_cast<int32_t>(b));
    }
    if (nearBodies[r].empty()) continue;
    if (isRound(*R.geometry)) {
      roundBodies.push_back(static_cast<int32_t>(r));
      continue;
    }
    rigidVertices(*R.geometry, &vertices);
    for (size_t k = 0; k < vertices.size(); ++k)
      corners.push_back({static_cast<int32_t>(r), static_cast<int32_t>(k), vertices[k]});
  }
  const size_t first = slots->size();
  slots->resize(first + corners.size());
  const int32_t deformables = static_cast<int32_t>(bodies.size());
  parallelFor(tasks, static_cast<int64_t>(corners.size()), 16, [&](int64_t begin, int64_t end) {
    for (int64_t k = begin; k < end; ++k) {
      const Corner& c = corners[static_cast<size_t>(k)];
      double lowest = std::numeric_limits<double>::infinity();
      for (int32_t b : nearBodies[static_cast<size_t>(c.rigid)])
        nearestTriangleToCorner(rigids[static_cast<size_t>(c.rigid)], deformables + c.rigid, c.index, c.position,
                                bodies, b, h, &lowest, &(*slots)[first + static_cast<size_t>(k)]);
    }
  });
  for (int32_t r : roundBodies)
    for (int32_t b : nearBodies[static_cast<size_t>(r)])
      roundContacts(rigids[static_cast<size_t>(r)], deformables + r, bodies, b, h, slots);
}

}  // namespace

void rigidVertices(const PreparedCollider& shape, Array<Vec3>* out) {
  out->clear();
  const ColliderShape& s = shape.shape;
  switch (s.kind) {
    case ShapeKind::Box:
      for (int k = 0; k < 8; ++k) {
        const Vec3 local((k & 1 ? 1.0 : -1.0) * s.halfExtents.x(), (k & 2 ? 1.0 : -1.0) * s.halfExtents.y(),
                         (k & 4 ? 1.0 : -1.0) * s.halfExtents.z());
        out->push_back(shape.rotation * local + shape.translation);
      }
      break;
    case ShapeKind::ConvexHull:
      for (const Vec3& p : s.hullPoints) out->push_back(shape.rotation * p + shape.translation);
      break;
    case ShapeKind::TriangleMesh: out->assign(shape.worldVertices.begin(), shape.worldVertices.end()); break;
    default: break;
  }
}

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
      const double reach = kPairContactKeep * A.rest + 1e-9 + R.sweep(h, A.surface->frameVelocity());
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
  findCornerContacts(bodies, rigids, h, tasks, &slots);
  for (PairContact& c : slots) {
    if (c.node < 0) continue;
    const CornerFriction* corner =
        c.rigidNode ? cornerState(bodies[c.triangleBody], c.nodeBodyId, c.node) : nullptr;
    const PairFriction& f = c.rigidNode ? (corner != nullptr ? corner->state : PairFriction())
                                        : (*bodies[c.nodeBody].friction)[c.node];
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
