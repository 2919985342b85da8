// Rotation R of a 3x3 deformation gradient F (F = R S) for corotational elasticity, as kernel
// bodies a CPU loop and a CUDA thread run alike (plain arrays, no allocation; matrices
// row-major, M[3*row + col]; quaternions (w, x, y, z)).
//
// R must stay a proper rotation (det R = +1) for every F the simulation can produce:
// degenerate (rank 0, 1, 2) when an element is crushed, and inverted (det F < 0) when it is
// pushed through itself. A reflection in R would turn the corotated force into one that
// keeps the element inverted; any rotation in R gives a force that pushes it back out.
//
// - polarRotationSvd: the reference, "invertible FEM" style (Irving et al. 2004). SVD
//   F = U Σ Vᵀ; if det(U Vᵀ) < 0 the column of U belonging to the smallest singular value is
//   negated (F then has Σ with its last entry negative, the least-deformation way to read an
//   inverted element); R = U Vᵀ. The result maximizes tr(Rᵀ F) over SO(3).
// - polarRotationIterative: warm-started iteration after Müller et al. 2016, "A robust
//   method to extract the rotational part of deformations": rotate a unit quaternion q by
//   ω until ω vanishes, where ω comes from g = Σ_i r_i × f_i (r_i, f_i the columns of R(q)
//   and F), the gradient of tr(Rᵀ F). Müller et al. take ω = g / |tr(Rᵀ F)|, which converges
//   linearly. We take the Newton step ω = (tr(B) I − sym(B))⁻¹ g, B = F Rᵀ, whenever that
//   matrix is positive definite, and their step otherwise: quadratic convergence, a few
//   iterations to round-off from a warm start. For det F <= 0 it defers to the SVD.
//
// Written by hand rather than with Eigen (which the CPU used before) because a CUDA thread runs
// them: only +, −, ×, ÷ and sqrt, all correctly rounded on both sides, so a device built with
// --fmad=false gives the CPU's bits. That is also why a step ω turns q by the rational
// quaternion (1, ω/2) — a turn of 2 atan(|ω|/2) about ω, equal to |ω| to third order, so the
// Newton iteration stays quadratic — rather than by cos and sin of |ω|/2, which differ between
// the C library and the device's.
#pragma once

#include <cmath>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

namespace polar_detail {

VP_HOST_DEVICE inline void setIdentity(double R[9]) {
  for (int i = 0; i < 9; ++i) R[i] = (i % 4 == 0) ? 1.0 : 0.0;
}

VP_HOST_DEVICE inline bool allFinite(const double* v, int count) {
  for (int i = 0; i < count; ++i)
    if (!(v[i] - v[i] == 0.0)) return false;  // inf − inf and NaN − NaN are NaN
  return true;
}

VP_HOST_DEVICE inline double determinant(const double m[9]) {
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
         m[2] * (m[3] * m[7] - m[4] * m[6]);
}

VP_HOST_DEVICE inline void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

VP_HOST_DEVICE inline double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Columns c and d of a row-major 3x3 rotated by the plane rotation (cs, sn).
VP_HOST_DEVICE inline void rotateColumns(double m[9], int c, int d, double cs, double sn) {
  for (int i = 0; i < 3; ++i) {
    const double mc = m[3 * i + c], md = m[3 * i + d];
    m[3 * i + c] = cs * mc - sn * md;
    m[3 * i + d] = sn * mc + cs * md;
  }
}

VP_HOST_DEVICE inline void swapColumns(double m[9], int c, int d) {
  for (int i = 0; i < 3; ++i) {
    const double t = m[3 * i + c];
    m[3 * i + c] = m[3 * i + d];
    m[3 * i + d] = t;
  }
}

VP_HOST_DEVICE inline void column(const double m[9], int c, double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = m[3 * i + c];
}

// Any unit vector perpendicular to the unit vector u: u crossed with the axis it is least
// aligned with.
VP_HOST_DEVICE inline void perpendicular(const double u[3], double out[3]) {
  const double ax = std::fabs(u[0]), ay = std::fabs(u[1]), az = std::fabs(u[2]);
  double axis[3] = {0.0, 0.0, 0.0};
  axis[ax <= ay && ax <= az ? 0 : (ay <= az ? 1 : 2)] = 1.0;
  cross(u, axis, out);
  const double n = std::sqrt(dot(out, out));
  for (int i = 0; i < 3; ++i) out[i] /= n;
}

// One-sided (Hestenes) Jacobi sweeps stop once every column pair is orthogonal to this
// relative cosine, or after kJacobiSweeps (3x3 converges quadratically in about five).
constexpr double kJacobiCosine = 1e-15;
constexpr int kJacobiSweeps = 20;

}  // namespace polar_detail

// Iteration limit and step tolerance (radians) of an element's rotation in a corotated step:
// warm-started from the last step's rotation it converges in two or three iterations.
constexpr int kCorotationIterations = 20;
constexpr double kCorotationTolerance = 1e-6;

// Eigen's Quaternion::toRotationMatrix, term for term.
VP_HOST_DEVICE inline void rotationFromQuaternion(const double quat[4], double R[9]) {
  const double w = quat[0], x = quat[1], y = quat[2], z = quat[3];
  const double tx = 2.0 * x, ty = 2.0 * y, tz = 2.0 * z;
  const double twx = tx * w, twy = ty * w, twz = tz * w;
  const double txx = tx * x, txy = ty * x, txz = tz * x;
  const double tyy = ty * y, tyz = tz * y, tzz = tz * z;
  R[0] = 1.0 - (tyy + tzz), R[1] = txy - twz, R[2] = txz + twy;
  R[3] = txy + twz, R[4] = 1.0 - (txx + tzz), R[5] = tyz - twx;
  R[6] = txz - twy, R[7] = tyz + twx, R[8] = 1.0 - (txx + tyy);
}

// Shepperd's method (Eigen's Quaternion from a rotation matrix): the largest of w, x, y, z is
// taken from the diagonal, the others from off-diagonal sums, so no square root of a small
// difference is taken.
VP_HOST_DEVICE inline void quaternionFromRotation(const double R[9], double quat[4]) {
  const double trace = R[0] + R[4] + R[8];
  if (trace > 0.0) {
    double t = std::sqrt(trace + 1.0);
    quat[0] = 0.5 * t;
    t = 0.5 / t;
    quat[1] = (R[7] - R[5]) * t;
    quat[2] = (R[2] - R[6]) * t;
    quat[3] = (R[3] - R[1]) * t;
    return;
  }
  int i = 0;
  if (R[4] > R[0]) i = 1;
  if (R[8] > R[4 * i]) i = 2;
  const int j = (i + 1) % 3, k = (j + 1) % 3;
  double t = std::sqrt(R[4 * i] - R[4 * j] - R[4 * k] + 1.0);
  quat[1 + i] = 0.5 * t;
  t = 0.5 / t;
  quat[0] = (R[3 * k + j] - R[3 * j + k]) * t;
  quat[1 + j] = (R[3 * j + i] + R[3 * i + j]) * t;
  quat[1 + k] = (R[3 * k + i] + R[3 * i + k]) * t;
}

// Returns false, and R = identity, when F has a non-finite entry (the caller's divergence
// guard reports it); true otherwise.
//
// One-sided Jacobi: plane rotations V on the right make the columns a_i of A = F V mutually
// orthogonal, so F = U Σ Vᵀ with σ_i = |a_i| and u_i = a_i / σ_i. With the columns sorted by σ,
// the proper rotation nearest F is R = u0 v0ᵀ + u1 v1ᵀ + (u0 × u1)(v0 × v1)ᵀ: the third terms
// are U's and V's last columns with the signs that make det R = +1, which is Irving's choice,
// and the smallest singular direction of F is never divided by. Rank 1 completes u1 with any
// perpendicular, rank 0 gives the identity: any rotation is valid there.
VP_HOST_DEVICE inline bool polarRotationSvd(const double F[9], double R[9]) {
  using namespace polar_detail;
  if (!allFinite(F, 9)) {
    setIdentity(R);
    return false;
  }
  // A = F scaled by a power of two to a largest entry in [1/2, 1), so that no squared column
  // norm overflows or underflows whatever F's magnitude; the scaling is exact and every step
  // below is homogeneous, so R's bits do not depend on it.
  double largest = 0.0;
  for (int i = 0; i < 9; ++i) largest = std::fmax(largest, std::fabs(F[i]));
  if (largest == 0.0) {
    setIdentity(R);
    return true;
  }
  int exponent = 0;
  std::frexp(largest, &exponent);
  double A[9], V[9];
  for (int i = 0; i < 9; ++i) A[i] = std::ldexp(F[i], -exponent);
  setIdentity(V);
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int sweep = 0; sweep < kJacobiSweeps; ++sweep) {
    bool orthogonal = true;
    for (const auto& pair : pairs) {
      const int p = pair[0], q = pair[1];
      double ap[3], aq[3];
      column(A, p, ap);
      column(A, q, aq);
      const double alpha = dot(ap, ap), beta = dot(aq, aq), gamma = dot(ap, aq);
      if (std::fabs(gamma) <= kJacobiCosine * std::sqrt(alpha * beta)) continue;
      orthogonal = false;
      // tan of the angle that zeroes a_p · a_q, the smaller root; zeta² would overflow
      // past 1e150, where the root is 1 / (2 zeta) to double precision.
      const double zeta = (beta - alpha) / (2.0 * gamma);
      const double z = std::fabs(zeta);
      const double t = (zeta >= 0.0 ? 1.0 : -1.0) * (z > 1e150 ? 0.5 / z : 1.0 / (z + std::sqrt(1.0 + z * z)));
      const double cs = 1.0 / std::sqrt(1.0 + t * t), sn = cs * t;
      rotateColumns(A, p, q, cs, sn);
      rotateColumns(V, p, q, cs, sn);
    }
    if (orthogonal) break;
  }
  double sigma[3];
  for (int c = 0; c < 3; ++c) {
    double a[3];
    column(A, c, a);
    sigma[c] = std::sqrt(dot(a, a));
  }
  // Sort descending, carrying the columns of A and V along.
  for (int pass = 0; pass < 2; ++pass)
    for (int c = 0; c < 2 - pass; ++c)
      if (sigma[c] < sigma[c + 1]) {
        const double s = sigma[c];
        sigma[c] = sigma[c + 1];
        sigma[c + 1] = s;
        swapColumns(A, c, c + 1);
        swapColumns(V, c, c + 1);
      }
  if (!(sigma[0] > 0.0)) {
    setIdentity(R);
    return true;
  }
  double u0[3], u1[3], v0[3], v1[3], u2[3], v2[3];
  column(A, 0, u0);
  for (int i = 0; i < 3; ++i) u0[i] /= sigma[0];
  column(A, 1, u1);
  // Gram–Schmidt keeps u1 orthogonal to u0 when σ1 is a rounding error away from 0.
  const double along = dot(u0, u1);
  for (int i = 0; i < 3; ++i) u1[i] -= along * u0[i];
  const double n1 = std::sqrt(dot(u1, u1));
  if (n1 > 1e-14 * sigma[0]) {
    for (int i = 0; i < 3; ++i) u1[i] /= n1;
  } else {
    perpendicular(u0, u1);
  }
  column(V, 0, v0);
  column(V, 1, v1);
  cross(u0, u1, u2);
  cross(v0, v1, v2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[3 * i + j] = u0[i] * v0[j] + u1[i] * v1[j] + u2[i] * v2[j];
  return true;
}

// quat: in, the warm start (e.g. the previous frame's rotation of this element; (1,0,0,0) for
// none; need not be normalized but must not be zero); out, the result, unit length. R receives
// its matrix. Iterates until the step |ω| < tolerance (radians) or maxIterations. Returns the
// number of iterations taken (0 when det F <= 0 and the SVD answered), or -1 when F is not
// finite (R = the normalized warm start, quat unchanged). q stays unit length, so R is a
// rotation even when the iteration stops early.
VP_HOST_DEVICE inline int polarRotationIterative(const double F[9], double quat[4], double R[9], int maxIterations,
                                                 double tolerance) {
  using namespace polar_detail;
  double q[4];
  const double qn = std::sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]);
  for (int i = 0; i < 4; ++i) q[i] = quat[i] / qn;
  if (!allFinite(F, 9)) {
    rotationFromQuaternion(q, R);
    return -1;
  }
  if (determinant(F) <= 0.0) {
    // Inverted or flat: the basin of Irving's rotation shrinks to nothing as σ2 − σ3 -> 0
    // (the Hessian eigenvalue σ2 − σ3 vanishes), and 0.5 rad warm starts were seen to end on
    // a wrong stationary point in up to half of such cases. Inversions are rare, so the SVD
    // costs nothing on average here.
    polarRotationSvd(F, R);
    quaternionFromRotation(R, quat);
    return 0;
  }
  rotationFromQuaternion(q, R);
  int iteration = 0;
  for (; iteration < maxIterations; ++iteration) {
    // g = Σ r_i × f_i is the gradient of tr(Rᵀ F) for a world-frame rotation exp([δ]) R;
    // its Hessian is −(tr(B) I − sym(B)) with B = F Rᵀ. Müller et al. step by g / |tr(B)|,
    // i.e. they approximate that matrix by tr(B) I, which near the optimum under-steps by a
    // factor of about 2/3. We take the Newton step when the matrix is positive definite
    // (always near the optimum, inverted elements included, since Irving's choice puts −σ3
    // on the smallest singular value) and fall back to their step otherwise (far from the
    // optimum, or a rank-deficient F), where it is a safe ascent direction.
    double g[3] = {0.0, 0.0, 0.0};
    for (int c = 0; c < 3; ++c) {
      double r[3], f[3], rf[3];
      column(R, c, r);
      column(F, c, f);
      cross(r, f, rf);
      for (int i = 0; i < 3; ++i) g[i] += rf[i];
    }
    double B[9];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) B[3 * a + b] = F[3 * a] * R[3 * b] + F[3 * a + 1] * R[3 * b + 1] + F[3 * a + 2] * R[3 * b + 2];
    const double trace = B[0] + B[4] + B[8];
    double H[9];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) H[3 * a + b] = (a == b ? trace : 0.0) - 0.5 * (B[3 * a + b] + B[3 * b + a]);
    // Cholesky H = L Lᵀ; a pivot that is not positive (or NaN) means no Newton step.
    double omega[3];
    bool newton = false;
    const double d0 = H[0];
    if (d0 > 0.0) {
      const double l00 = std::sqrt(d0), l10 = H[3] / l00, l20 = H[6] / l00;
      const double d1 = H[4] - l10 * l10;
      if (d1 > 0.0) {
        const double l11 = std::sqrt(d1), l21 = (H[7] - l20 * l10) / l11;
        const double d2 = H[8] - l20 * l20 - l21 * l21;
        if (d2 > 0.0) {
          const double l22 = std::sqrt(d2);
          const double y0 = g[0] / l00, y1 = (g[1] - l10 * y0) / l11, y2 = (g[2] - l20 * y0 - l21 * y1) / l22;
          omega[2] = y2 / l22;
          omega[1] = (y1 - l21 * omega[2]) / l11;
          omega[0] = (y0 - l10 * omega[1] - l20 * omega[2]) / l00;
          // A nearly singular Hessian (rank-deficient F) gives a huge, meaningless step.
          newton = allFinite(omega, 3) && dot(omega, omega) < 1.0;
        }
      }
    }
    // The 1e-9 only prevents a division by zero (tr = 0 happens for F = 0).
    if (!newton)
      for (int i = 0; i < 3; ++i) omega[i] = g[i] / (std::fabs(trace) + 1e-9);
    if (std::sqrt(dot(omega, omega)) < tolerance) break;
    // q ← normalize((1, ω/2) q).
    const double h[3] = {0.5 * omega[0], 0.5 * omega[1], 0.5 * omega[2]};
    const double v[3] = {q[1], q[2], q[3]};
    double hv[3];
    cross(h, v, hv);
    double next[4] = {q[0] - dot(h, v), v[0] + q[0] * h[0] + hv[0], v[1] + q[0] * h[1] + hv[1],
                      v[2] + q[0] * h[2] + hv[2]};
    const double n = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2] + next[3] * next[3]);
    for (int i = 0; i < 4; ++i) q[i] = next[i] / n;
    rotationFromQuaternion(q, R);
  }
  for (int i = 0; i < 4; ++i) quat[i] = q[i];
  return iteration;
}

}  // namespace vp::kernels
