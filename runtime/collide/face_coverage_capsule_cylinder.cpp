// Face coverage by a capsule or a cylinder in any pose.
//
// Method (error bound guaranteed, no sampling guesswork):
//  1. Along each face line v = const (direction u) the solid is convex, so line ∩ solid is one
//     interval, computed exactly (ray vs. spheres / infinite cylinder / slab). The chord
//     f(v) = |[u0,u1] ∩ interval| is therefore exact.
//  2. S = square ∩ cross-section is convex, so f is concave on its support [p, q] and 0
//     outside. On [a, b] ⊂ [p, q] with midpoint m, concavity bounds the integral between the
//     two-trapezoid sum and the sum over the secant extensions; the gap is
//     (b - a) (f(m) - (f(a) + f(b)) / 2). Intervals are split until half the gap is below
//     their share of the tolerance; the estimate is the middle of the bounds.
//  3. The support ends are bracketed by bisection between a zero and a positive sample down to
//     width delta; the area in a bracket is at most delta * W (W = face width), delta chosen so
//     that both brackets together cost at most tol / 4.
//  4. If no sample line (9 per direction, both directions tried) meets S, S lies inside one
//     cell of the 8 x 8 sample grid. Cells that the solid's signed distance proves empty are
//     skipped, the others are treated recursively; a cell whose area is below the tolerance
//     returns 0 (S fits in it, so the error is at most that area).
// Total error <= tol = 0.9 * kCoverageTolerance * (face area).
#include "collide/face_coverage_detail.h"

namespace vp {
namespace detail {
namespace {

constexpr double kAll = 1e300;

struct Interval {
  double lo = kAll, hi = -kAll;  // empty
  bool empty() const { return lo > hi; }
  void hull(const Interval& o) {
    if (o.empty()) return;
    lo = std::min(lo, o.lo);
    hi = std::max(hi, o.hi);
  }
  void intersect(const Interval& o) {
    lo = std::max(lo, o.lo);
    hi = std::min(hi, o.hi);
  }
};

// Line p + s d (|d| = 1) against the ball |x - (0, y, 0)| <= r.
Interval lineBall(const Eigen::Vector3d& p, const Eigen::Vector3d& d, double y, double r) {
  const Eigen::Vector3d w(p.x(), p.y() - y, p.z());
  const double b = d.dot(w), disc = b * b - (w.squaredNorm() - r * r);
  Interval iv;
  if (disc < 0.0) return iv;
  const double q = std::sqrt(disc);
  iv.lo = -b - q;
  iv.hi = -b + q;
  return iv;
}

// Line against the infinite cylinder x^2 + z^2 <= r^2.
Interval lineInfiniteCylinder(const Eigen::Vector3d& p, const Eigen::Vector3d& d, double r) {
  const double A = d.x() * d.x() + d.z() * d.z();
  const double B = p.x() * d.x() + p.z() * d.z();
  const double C = p.x() * p.x() + p.z() * p.z() - r * r;
  Interval iv;
  if (A < 1e-24) {
    if (C <= 0.0) { iv.lo = -kAll; iv.hi = kAll; }
    return iv;
  }
  const double disc = B * B - A * C;
  if (disc < 0.0) return iv;
  const double q = std::sqrt(disc);
  iv.lo = (-B - q) / A;
  iv.hi = (-B + q) / A;
  return iv;
}

// Line against the slab |y| <= hh.
Interval lineSlab(const Eigen::Vector3d& p, const Eigen::Vector3d& d, double hh) {
  Interval iv;
  if (std::fabs(d.y()) < 1e-12) {
    if (std::fabs(p.y()) <= hh) { iv.lo = -kAll; iv.hi = kAll; }
    return iv;
  }
  const double s0 = (-hh - p.y()) / d.y(), s1 = (hh - p.y()) / d.y();
  iv.lo = std::min(s0, s1);
  iv.hi = std::max(s0, s1);
  return iv;
}

// Exact chords of the solid along lines of one in-plane direction.
struct ChordFunction {
  const PreparedCollider* c;
  Eigen::Vector3d origin;  // local coordinates of the world point (c0 e_a) shifted by -t
  Eigen::Vector3d dirLine; // local direction along the line (unit)
  Eigen::Vector3d dirStep; // local direction across lines (unit)
  double s0, s1;           // clip range along the line

  double operator()(double w) const {
    const Eigen::Vector3d p = origin + w * dirStep;
    const double r = c->shape.radius, hh = c->shape.halfHeight;
    Interval iv = lineInfiniteCylinder(p, dirLine, r);
    iv.intersect(lineSlab(p, dirLine, hh));
    if (c->shape.kind == ShapeKind::Capsule) {
      if (iv.lo > iv.hi) iv = Interval();
      iv.hull(lineBall(p, dirLine, hh, r));
      iv.hull(lineBall(p, dirLine, -hh, r));
    }
    return std::max(0.0, std::min(iv.hi, s1) - std::max(iv.lo, s0));
  }
};

double adaptConcave(const ChordFunction& f, double a, double b, double fa, double fb, double tol,
                    int depth) {
  const double m = 0.5 * (a + b), fm = f(m);
  const double gap = std::fabs((b - a) * (fm - 0.5 * (fa + fb)));
  const double lower = 0.25 * (b - a) * (fa + 2.0 * fm + fb);
  if (0.5 * gap <= tol || depth >= 48) return lower + 0.5 * gap;
  return adaptConcave(f, a, m, fa, fm, 0.5 * tol, depth + 1) +
         adaptConcave(f, m, b, fm, fb, 0.5 * tol, depth + 1);
}

// Integral of f over [w0, w1] with error <= tol, or -1 when no sample line meets the solid.
double integrateChords(const ChordFunction& f, double w0, double w1, double tol) {
  constexpr int N = 8;
  double ws[N + 1], fs[N + 1];
  int first = -1, last = -1;
  for (int i = 0; i <= N; ++i) {
    ws[i] = (i == N) ? w1 : w0 + (w1 - w0) * i / N;
    fs[i] = f(ws[i]);
    if (fs[i] > 0.0) {
      if (first < 0) first = i;
      last = i;
    }
  }
  if (first < 0) return -1.0;
  const double W = f.s1 - f.s0;
  const double delta = 0.125 * tol / W;  // each support bracket costs <= tol / 8
  double area = 0.0;
  double pl = ws[first], fpl = fs[first];
  if (first > 0) {
    double z = ws[first - 1];
    while (pl - z > delta) {
      const double m = 0.5 * (z + pl), fm = f(m);
      if (fm > 0.0) { pl = m; fpl = fm; } else { z = m; }
    }
    area += 0.5 * (pl - z) * fpl;
  }
  double pr = ws[last], fpr = fs[last];
  if (last < N) {
    double z = ws[last + 1];
    while (z - pr > delta) {
      const double m = 0.5 * (z + pr), fm = f(m);
      if (fm > 0.0) { pr = m; fpr = fm; } else { z = m; }
    }
    area += 0.5 * (z - pr) * fpr;
  }
  const double span = pr - pl;
  if (span <= 0.0) return area;
  const double tolInt = 0.5 * tol;
  // Knots pl, ws[first..last] (interior), pr; all have f > 0, so f is concave across them.
  double a = pl, fa = fpl;
  for (int i = first; i <= last + 1; ++i) {
    double b, fb;
    if (i <= last && ws[i] > a && ws[i] < pr) { b = ws[i]; fb = fs[i]; }
    else if (i == last + 1) { b = pr; fb = fpr; }
    else continue;
    if (b > a) area += adaptConcave(f, a, b, fa, fb, tolInt * (b - a) / span, 0);
    a = b;
    fa = fb;
  }
  return area;
}

double coveredAreaRect(const PreparedCollider& c, const FaceFrame& fr, double u0, double u1,
                       double v0, double v1, double tol, int depth) {
  const Eigen::Matrix3d& R = c.rotation;
  Eigen::Vector3d base = Eigen::Vector3d::Zero();
  base[fr.a] = fr.c0;
  const Eigen::Vector3d origin = R.transpose() * (base - c.translation);
  const Eigen::Vector3d du = R.row(fr.a1).transpose(), dv = R.row(fr.a2).transpose();
  // Lines along u, stepping in v.
  ChordFunction fu{&c, origin, du, dv, u0, u1};
  double area = integrateChords(fu, v0, v1, tol);
  if (area >= 0.0) return area;
  ChordFunction fv{&c, origin, dv, du, v0, v1};
  area = integrateChords(fv, u0, u1, tol);
  if (area >= 0.0) return area;
  // No sample line meets S: S (if any) lies inside one cell of the 8 x 8 sample grid.
  const double cu = (u1 - u0) / 8, cv = (v1 - v0) / 8;
  if (cu * cv <= tol || depth >= 6) return 0.0;
  const double halfDiag = 0.5 * std::sqrt(cu * cu + cv * cv);
  double sum = 0.0;
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 8; ++i) {
      Eigen::Vector3d x = base;
      x[fr.a1] = u0 + (i + 0.5) * cu;
      x[fr.a2] = v0 + (j + 0.5) * cv;
      if (signedDistanceBound(c, x) >= halfDiag) continue;
      sum += coveredAreaRect(c, fr, u0 + i * cu, u0 + (i + 1) * cu, v0 + j * cv,
                             v0 + (j + 1) * cv, tol, depth + 1);
    }
  }
  return sum;
}

}  // namespace

double coveredAreaCapsuleOrCylinder(const PreparedCollider& c, const FaceFrame& fr) {
  const double tol = 0.9 * kCoverageTolerance * fr.area();
  return coveredAreaRect(c, fr, fr.u0, fr.u1, fr.v0, fr.v1, tol, 0);
}

}  // namespace detail
}  // namespace vp
