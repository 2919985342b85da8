// Coverage of one face by several colliders: the area of a union is not the sum.
//
// Policy:
//  - colliders the conservative test proves outside are dropped; one proven to cover the
//    whole face gives 1;
//  - one collider left: its exact (or bounded) per-shape path;
//  - at most four left, all convex polyhedra (plane, box, hull) but at most one sphere: exact
//    by inclusion-exclusion, each intersection being the face square clipped by the
//    polyhedra's half-planes (and, with the sphere, its area inside the sphere's disc);
//  - otherwise their individual fractions a_i bound the union in [max a_i, min(1, Σ a_i)];
//    when that interval is narrower than the tolerance (e.g. all but one are 0, the common
//    case of overlapping bounding boxes but disjoint solids) its midpoint is exact enough;
//  - otherwise a quadtree over the face on phi = min_i phi_i (1-Lipschitz, negative inside
//    the union). A cell of side s whose centre has |phi| >= s/sqrt(2) is entirely inside or
//    outside. A leaf cell still undecided has covered area in
//    [0, s^2 - D(phi)] (phi > 0) or [D(|phi|), s^2] (phi < 0), D(r) = area of the disc of
//    radius r about the centre inside the cell; the leaf estimate (straight-edge guess
//    (1/2 - phi/s) s^2, clamped into that interval) is off by at most the larger distance
//    to the interval ends. The depth grows (4 .. 11) until the summed bound is below
//    kCoverageTolerance * face area, so the result is within the tolerance whenever the
//    loop ends by the bound (it always does for boundaries of finite length at depth 11
//    in practice; the cap keeps the cost finite for pathological inputs).
#include "collide/face_coverage_detail.h"

namespace vp {
namespace {

struct UnionQuadtree {
  const PreparedCollider* const* colliders;
  const int* active;
  int count;
  detail::FaceFrame fr;
  int maxDepth;
  double estimate = 0.0, bound = 0.0;

  double phi(double u, double v) const {
    Eigen::Vector3d x;
    x[fr.a] = fr.c0;
    x[fr.a1] = u;
    x[fr.a2] = v;
    double d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < count; ++i) d = std::min(d, signedDistanceBound(*colliders[active[i]], x));
    return d;
  }

  void visit(double u, double v, double s, int depth) {
    const double d = phi(u, v), halfDiag = 0.70710678118654757 * s, s2 = s * s;
    if (d >= halfDiag) return;
    if (d <= -halfDiag) { estimate += s2; return; }
    if (depth < maxDepth) {
      const double q = 0.25 * s;
      visit(u - q, v - q, 0.5 * s, depth + 1);
      visit(u + q, v - q, 0.5 * s, depth + 1);
      visit(u - q, v + q, 0.5 * s, depth + 1);
      visit(u + q, v + q, 0.5 * s, depth + 1);
      return;
    }
    const double r = std::fabs(d);
    const double disc = detail::discRectangleArea(0, 0, r, -0.5 * s, -0.5 * s, 0.5 * s, 0.5 * s);
    const double lo = d >= 0.0 ? 0.0 : disc, hi = d >= 0.0 ? s2 - disc : s2;
    const double est = std::min(hi, std::max(lo, (0.5 - d / s) * s2));
    estimate += est;
    bound += std::max(est - lo, hi - est);
  }
};

constexpr int kMaxExactUnion = 4;
// All the polyhedra's half-planes clip one polygon, so their total is bounded like a hull's.
using ClipPolygon = detail::FixedPolygon<kMaxConvexPlanes + 4>;

bool isHalfSpaceSolid(const PreparedCollider& c) {
  return c.shape.kind == ShapeKind::Box || c.shape.kind == ShapeKind::Plane || c.shape.kind == ShapeKind::ConvexHull;
}

// Whether exactUnionArea can take these colliders.
bool exactUnionApplies(const PreparedCollider* const* colliders, const int* active, int count) {
  if (count > kMaxExactUnion) return false;
  int spheres = 0;
  size_t planes = 0;
  for (int i = 0; i < count; ++i) {
    const PreparedCollider& c = *colliders[active[i]];
    if (c.shape.kind == ShapeKind::Sphere) ++spheres;
    else if (isHalfSpaceSolid(c)) planes += c.worldPlanes.size();
    else return false;
  }
  return spheres <= 1 && planes <= static_cast<size_t>(kMaxConvexPlanes);
}

// Area of the union by inclusion-exclusion over the subsets of the colliders.
double exactUnionArea(const PreparedCollider* const* colliders, const int* active, int count,
                      const detail::FaceFrame& fr) {
  double area = 0.0;
  ClipPolygon poly;
  for (int subset = 1; subset < (1 << count); ++subset) {
    poly.setRect(fr.u0, fr.v0, fr.u1, fr.v1);
    const PreparedCollider* sphere = nullptr;
    bool empty = false;
    for (int i = 0; i < count && !empty; ++i) {
      if (!((subset >> i) & 1)) continue;
      const PreparedCollider& c = *colliders[active[i]];
      if (c.shape.kind == ShapeKind::Sphere) sphere = &c;
      else empty = !detail::clipByHalfSpaces(poly, c.worldPlanes.data(), static_cast<int>(c.worldPlanes.size()), fr);
    }
    if (empty) continue;
    double part = poly.area();
    if (sphere != nullptr) {
      double cu, cv, r;
      part = detail::sphereCrossSection(*sphere, fr, &cu, &cv, &r) ? detail::discPolygonArea(cu, cv, r, poly.x, poly.y, poly.n)
                                                                   : 0.0;
    }
    area += (__builtin_popcount(static_cast<unsigned>(subset)) & 1) ? part : -part;
  }
  return area;
}

}  // namespace

double coveredFractionUnion(const PreparedCollider* const* colliders, int count,
                            const AxisFace& face) {
  constexpr int kMaxActive = 64;
  int active[kMaxActive];
  int n = 0;
  for (int i = 0; i < count; ++i) {
    const int cls = classifyFace(*colliders[i], face);
    if (cls > 0) return 1.0;
    if (cls == 0 && n < kMaxActive) active[n++] = i;
  }
  if (n == 0) return 0.0;
  if (n == 1) return coveredFraction(*colliders[active[0]], face);
  // Deforming surfaces (deformables) are kept out of the other solids by their contacts, so
  // their covered parts of a face do not overlap the others': their coverages add. Only the
  // rigid solids, which may overlap each other, go through the union below.
  double deforming = 0.0;
  int rigid = 0;
  for (int i = 0; i < n; ++i) {
    if (colliders[active[i]]->vertexVelocities.empty()) active[rigid++] = active[i];
    else deforming += coveredFraction(*colliders[active[i]], face);
  }
  if (rigid < n) {
    const PreparedCollider* rigidOnes[kMaxActive];
    for (int i = 0; i < rigid; ++i) rigidOnes[i] = colliders[active[i]];
    return std::min(1.0, deforming + (rigid > 0 ? coveredFractionUnion(rigidOnes, rigid, face) : 0.0));
  }
  const detail::FaceFrame frame = detail::makeFrame(face);
  if (exactUnionApplies(colliders, active, n))
    return std::min(1.0, std::max(0.0, exactUnionArea(colliders, active, n, frame) / frame.area()));
  double maxA = 0.0, sumA = 0.0;
  for (int i = 0; i < n; ++i) {
    const double a = coveredFraction(*colliders[active[i]], face);
    maxA = std::max(maxA, a);
    sumA += a;
  }
  const double upper = std::min(1.0, sumA);
  if (upper - maxA <= kCoverageTolerance) return 0.5 * (upper + maxA);
  if (maxA >= 1.0) return 1.0;

  UnionQuadtree qt{colliders, active, n, frame, 0};
  const double tol = kCoverageTolerance * face.h * face.h;
  const double uc = face.centre[qt.fr.a1], vc = face.centre[qt.fr.a2];
  for (int depth = 4; depth <= 11; ++depth) {
    qt.maxDepth = depth;
    qt.estimate = qt.bound = 0.0;
    qt.visit(uc, vc, face.h, 0);
    if (qt.bound <= tol) break;
  }
  const double f = qt.estimate / (face.h * face.h);
  return std::min(upper, std::max(maxA, f));
}

}  // namespace vp
