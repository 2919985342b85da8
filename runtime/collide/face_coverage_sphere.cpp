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

double coveredAreaSphere(const PreparedCollider& c, const FaceFrame& fr) {
  const Eigen::Vector3d& ctr = c.translation;
  const double dz = fr.c0 - ctr[fr.a];
  const double rho2 = c.shape.radius * c.shape.radius - dz * dz;
  if (rho2 <= 0.0) return 0.0;
  return discRectangleArea(ctr[fr.a1], ctr[fr.a2], std::sqrt(rho2), fr.u0, fr.v0, fr.u1, fr.v1);
}

}  // namespace detail
}  // namespace vp
