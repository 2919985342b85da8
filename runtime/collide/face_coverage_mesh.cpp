// Face coverage by a closed triangle mesh: exact, via Green's theorem on the cross-section.
//
// The mesh ∩ face plane is a set of closed, consistently oriented polygons made of one segment
// per crossing triangle. For a region R with counter-clockwise boundary (interior on the left,
// in the face's right-handed (u, v) frame) and the rectangle [u0,u1]x[v0,v1],
//   area(R ∩ rect) = - ∮_{∂R} (clamp(v, v0, v1) - v0) du,  u restricted to [u0, u1],
// because along every line u = const the boundary crossings pair up into the inside
// intervals and the clamp clips them to [v0, v1]. Each segment contributes a piecewise-linear
// integral, split where v crosses v0 and v1: exact.
//
// Needed segments are those whose u-range meets [u0, u1] and that reach above v0 (segments
// above the face contribute (v1 - v0) du), found by a BVH box query over that column.
// The first moments follow the same way: ∫∫ u dA = - ∮ u (clamp(v) - v0) du and
// ∫∫ v dA = - ∮ ½ (clamp(v)² - v0²) du, piecewise polynomials of degree at most two in u,
// which Simpson's rule integrates exactly.
// Consistency: a vertex exactly on the plane counts as above it (symbolic perturbation), the
// crossing point of an edge is computed from its endpoints in index order (so both triangles
// sharing the edge get bit-identical points) and a segment's direction follows from the
// triangle's vertex order, not from a rounding-sensitive normal.
#include "collide/face_coverage_detail.h"

namespace vp {
namespace detail {
namespace {

// Over [lo, hi] for a line v(u) through (ua, va), (ub, vb), with f = clamp(v, v0, v1) - v0:
// ∫ f du, and when `moments`, ∫ u f du and ∫ ½ (clamp(v)² - v0²) du; exact.
CoveredMoments clampedIntegrals(double ua, double va, double ub, double vb, double lo, double hi, double v0,
                                double v1, bool moments) {
  const double k = (vb - va) / (ub - ua);
  auto vAt = [&](double u) { return va + k * (u - ua); };
  double knots[4];
  int n = 0;
  knots[n++] = lo;
  if (k != 0.0) {
    for (double level : {v0, v1}) {
      const double u = ua + (level - va) / k;
      if (u > lo && u < hi) knots[n++] = u;
    }
  }
  knots[n++] = hi;
  if (n == 4 && knots[1] > knots[2]) std::swap(knots[1], knots[2]);
  CoveredMoments s;
  for (int i = 0; i + 1 < n; ++i) {
    const double a = knots[i], b = knots[i + 1];
    if (b <= a) continue;
    const double m = 0.5 * (a + b), vm = vAt(m);
    if (vm <= v0) continue;
    if (vm >= v1) {
      s.area += (v1 - v0) * (b - a);
      if (moments) {
        s.u += (v1 - v0) * m * (b - a);
        s.v += 0.5 * (v1 * v1 - v0 * v0) * (b - a);
      }
      continue;
    }
    s.area += 0.5 * (vAt(a) + vAt(b) - 2.0 * v0) * (b - a);
    if (moments) {
      const double fa = vAt(a) - v0, fm = vm - v0, fb = vAt(b) - v0;
      auto g = [&](double v) { return 0.5 * (v * v - v0 * v0); };
      s.u += (b - a) / 6.0 * (a * fa + 4.0 * m * fm + b * fb);
      s.v += (b - a) / 6.0 * (g(vAt(a)) + 4.0 * g(vm) + g(vAt(b)));
    }
  }
  return s;
}

// The part of segment p -> q inside the face's rectangle, as parameters [*t0, *t1] along it
// (Liang-Barsky); false when none of it, or a single point, is inside.
bool clipToFace(double pu, double pv, double qu, double qv, const FaceFrame& fr, double* t0, double* t1) {
  double lo = 0.0, hi = 1.0;
  const double d[2] = {qu - pu, qv - pv}, p[2] = {pu, pv}, low[2] = {fr.u0, fr.v0}, high[2] = {fr.u1, fr.v1};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (p[k] < low[k] || p[k] > high[k]) return false;
      continue;
    }
    double a = (low[k] - p[k]) / d[k], b = (high[k] - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
  *t0 = lo;
  *t1 = hi;
  return hi > lo;
}

CoveredMoments meshIntegrals(const PreparedCollider& c, const FaceFrame& fr, bool moments,
                             SurfaceTrace* trace = nullptr) {
  Eigen::Vector3d lo, hi;
  lo[fr.a] = hi[fr.a] = fr.c0;
  lo[fr.a1] = fr.u0;
  hi[fr.a1] = fr.u1;
  lo[fr.a2] = fr.v0;
  hi[fr.a2] = c.bounds.hi[fr.a2];
  CoveredMoments sum;
  if (hi[fr.a2] < lo[fr.a2]) return sum;
  const Array<Eigen::Vector3d>& V = c.worldVertices;
  bvhQueryBox(c.bvh, lo, hi, [&](int t) {
    const Eigen::Vector3i& tri = c.triangles[t];
    bool above[3];
    for (int k = 0; k < 3; ++k) above[k] = V[tri[k]][fr.a] >= fr.c0;
    if (above[0] == above[1] && above[1] == above[2]) return;
    int lone = 0;  // the vertex on its own side
    if (above[1] != above[0] && above[1] != above[2]) lone = 1;
    if (above[2] != above[0] && above[2] != above[1]) lone = 2;
    auto cross = [&](int i, int j, double* u, double* v, Eigen::Vector3d* velocity) {
      int p = tri[i], q = tri[j];
      if (p > q) std::swap(p, q);
      const double s = (fr.c0 - V[p][fr.a]) / (V[q][fr.a] - V[p][fr.a]);
      *u = V[p][fr.a1] + s * (V[q][fr.a1] - V[p][fr.a1]);
      *v = V[p][fr.a2] + s * (V[q][fr.a2] - V[p][fr.a2]);
      if (trace != nullptr) *velocity = c.vertexVelocities[p] + s * (c.vertexVelocities[q] - c.vertexVelocities[p]);
    };
    double pu, pv, qu, qv;
    Eigen::Vector3d pVelocity, qVelocity;
    cross(lone, (lone + 1) % 3, &pu, &pv, &pVelocity);
    cross((lone + 2) % 3, lone, &qu, &qv, &qVelocity);
    double t0, t1;
    if (trace != nullptr && clipToFace(pu, pv, qu, qv, fr, &t0, &t1)) {
      // The velocity is linear along the segment: its mean over the clipped part is its value
      // at that part's middle.
      const double length = (t1 - t0) * std::sqrt((qu - pu) * (qu - pu) + (qv - pv) * (qv - pv));
      trace->length += length;
      trace->velocity += length * (pVelocity + 0.5 * (t0 + t1) * (qVelocity - pVelocity));
    }
    // Lone vertex above: the boundary runs P -> Q; below: Q -> P.
    if (!above[lone]) { std::swap(pu, qu); std::swap(pv, qv); }
    if (pu == qu) return;
    const double l = std::max(std::min(pu, qu), fr.u0), h = std::min(std::max(pu, qu), fr.u1);
    if (h <= l) return;
    const CoveredMoments part = clampedIntegrals(pu, pv, qu, qv, l, h, fr.v0, fr.v1, moments);
    const double sign = (qu > pu) ? -1.0 : 1.0;
    sum.area += sign * part.area;
    sum.u += sign * part.u;
    sum.v += sign * part.v;
  });
  return sum;
}

}  // namespace

double coveredAreaMesh(const PreparedCollider& c, const FaceFrame& fr) {
  return std::min(fr.area(), std::max(0.0, meshIntegrals(c, fr, false).area));
}

double coveredAreaAndTraceMesh(const PreparedCollider& c, const FaceFrame& fr, SurfaceTrace* trace) {
  return std::min(fr.area(), std::max(0.0, meshIntegrals(c, fr, false, trace).area));
}

CoveredMoments coveredMomentsMesh(const PreparedCollider& c, const FaceFrame& fr) {
  CoveredMoments m = meshIntegrals(c, fr, true);
  m.area = std::min(fr.area(), std::max(0.0, m.area));
  return m;
}

}  // namespace detail
}  // namespace vp
