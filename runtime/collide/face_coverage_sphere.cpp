// Face coverage by a sphere: the cross-section is a disc of radius sqrt(r^2 - dz^2); its area
// inside the face rectangle is computed in closed form.
//
// discRectangleArea integrates the chord length L(x) = |[y0,y1] ∩ [-s(x), s(x)]|,
// s(x) = sqrt(R^2 - x^2), over x. Between the breakpoints {x0, x1, ±R, ±sqrt(R^2 - y0^2),
// ±sqrt(R^2 - y1^2)} each bound of the chord is either a rectangle side (constant) or the
// circle (±s(x)), so every piece integrates exactly with the primitive of s:
// P(x) = (x s(x) + R^2 asin(x/R)) / 2 (the circular-segment formula). At most 7 pieces.
#include "collide/face_coverage_detail.h"

namespace vp {
namespace detail {
namespace {

double primitiveS(double x, double r) {
  const double t = std::min(1.0, std::max(-1.0, x / r));
  const double s = std::sqrt(std::max(0.0, r * r - x * x));
  return 0.5 * (x * s + r * r * std::asin(t));
}

}  // namespace

double discRectangleArea(double cx, double cy, double r, double x0, double y0, double x1,
                         double y1) {
  if (!(r > 0.0) || x1 <= x0 || y1 <= y0) return 0.0;
  x0 -= cx; x1 -= cx; y0 -= cy; y1 -= cy;
  const double lo = std::max(x0, -r), hi = std::min(x1, r);
  if (hi <= lo || y0 >= r || y1 <= -r) return 0.0;
  double knots[8];
  int n = 0;
  knots[n++] = lo;
  knots[n++] = hi;
  for (double y : {y0, y1}) {
    if (std::fabs(y) < r) {
      const double xs = std::sqrt(r * r - y * y);
      if (xs > lo && xs < hi) knots[n++] = xs;
      if (-xs > lo && -xs < hi) knots[n++] = -xs;
    }
  }
  for (int i = 1; i < n; ++i)  // insertion sort, n <= 6
    for (int j = i; j > 0 && knots[j] < knots[j - 1]; --j) std::swap(knots[j], knots[j - 1]);
  double area = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    const double a = knots[i], b = knots[i + 1];
    if (b <= a) continue;
    const double m = 0.5 * (a + b);
    const double s = std::sqrt(std::max(0.0, r * r - m * m));
    const bool topIsCircle = s < y1, botIsCircle = -s > y0;
    const double top = topIsCircle ? s : y1, bot = botIsCircle ? -s : y0;
    if (top <= bot) continue;
    const double circle = primitiveS(b, r) - primitiveS(a, r);  // ∫ s dx
    const double width = b - a;
    area += (topIsCircle ? circle : y1 * width) - (botIsCircle ? -circle : y0 * width);
  }
  return std::max(0.0, area);
}

bool sphereCrossSection(const PreparedCollider& c, const FaceFrame& fr, double* cu, double* cv, double* radius) {
  const Eigen::Vector3d& ctr = c.translation;
  const double dz = fr.c0 - ctr[fr.a];
  const double rho2 = c.shape.radius * c.shape.radius - dz * dz;
  if (!(rho2 > 0.0)) return false;
  *cu = ctr[fr.a1];
  *cv = ctr[fr.a2];
  *radius = std::sqrt(rho2);
  return true;
}

double coveredAreaSphere(const PreparedCollider& c, const FaceFrame& fr) {
  double cu, cv, r;
  if (!sphereCrossSection(c, fr, &cu, &cv, &r)) return 0.0;
  return discRectangleArea(cu, cv, r, fr.u0, fr.v0, fr.u1, fr.v1);
}

namespace {

// Signed area of the disc of radius r about the origin inside the triangle (origin, p, q):
// the segment pq is cut where it crosses the circle, and each piece contributes its triangle
// with the origin when inside the disc, else the circular sector it subtends.
double discTriangleArea(double px, double py, double qx, double qy, double r) {
  const double dx = qx - px, dy = qy - py;
  const double a = dx * dx + dy * dy, b = px * dx + py * dy, c = px * px + py * py - r * r;
  double cuts[4] = {0.0, 0.0, 0.0, 1.0};
  int n = 1;
  const double disc = b * b - a * c;
  if (a > 0.0 && disc > 0.0) {
    const double root = std::sqrt(disc);
    for (double t : {(-b - root) / a, (-b + root) / a})
      if (t > 0.0 && t < 1.0) cuts[n++] = t;
  }
  cuts[n++] = 1.0;
  double area = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    const double t0 = cuts[i], t1 = cuts[i + 1], tm = 0.5 * (t0 + t1);
    const double x0 = px + t0 * dx, y0 = py + t0 * dy, x1 = px + t1 * dx, y1 = py + t1 * dy;
    const double mx = px + tm * dx, my = py + tm * dy;
    const double cross = x0 * y1 - x1 * y0;
    if (mx * mx + my * my <= r * r) area += 0.5 * cross;
    else area += 0.5 * r * r * std::atan2(cross, x0 * x1 + y0 * y1);
  }
  return area;
}

}  // namespace

double discPolygonArea(double cx, double cy, double r, const double* x, const double* y, int n) {
  if (!(r > 0.0) || n < 3) return 0.0;
  double area = 0.0;
  for (int i = 0; i < n; ++i) {
    const int j = i + 1 < n ? i + 1 : 0;
    area += discTriangleArea(x[i] - cx, y[i] - cy, x[j] - cx, y[j] - cy, r);
  }
  return std::fabs(area);
}

}  // namespace detail
}  // namespace vp
