#include "deform/polar_decomposition.h"

#include <Eigen/Dense>
#include <cmath>

namespace vp {
namespace {

using Mat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

bool allFinite(const double* v, int count) {
  for (int i = 0; i < count; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

void store(const Eigen::Matrix3d& m, double out[9]) {
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out[3 * a + b] = m(a, b);
}

void setIdentity(double R[9]) {
  for (int i = 0; i < 9; ++i) R[i] = (i % 4 == 0) ? 1.0 : 0.0;
}

}  // namespace

bool polarRotationSvd(const double F[9], double R[9]) {
  if (!allFinite(F, 9)) {
    setIdentity(R);
    return false;
  }
  // Two-sided Jacobi on a fixed 3x3 needs no QR preconditioner and no heap. U and V are
  // accumulated plane rotations, hence orthogonal even when F is rank deficient or zero.
  const Eigen::Map<const Mat3> f(F);
  const Eigen::JacobiSVD<Eigen::Matrix3d, Eigen::NoQRPreconditioner> svd(
      f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d& v = svd.matrixV();
  // Singular values come sorted descending, so column 2 is the smallest one: flipping it
  // changes F's reading the least, and for det F < 0 puts the inversion on the axis that is
  // already the most compressed.
  if (u.determinant() * v.determinant() < 0.0) u.col(2) = -u.col(2);
  store(u * v.transpose(), R);
  return true;
}

void rotationFromQuaternion(const double quat[4], double R[9]) {
  const Eigen::Quaterniond q(quat[0], quat[1], quat[2], quat[3]);
  store(q.toRotationMatrix(), R);
}

void quaternionFromRotation(const double R[9], double quat[4]) {
  const Eigen::Matrix3d m = Eigen::Map<const Mat3>(R);
  const Eigen::Quaterniond q(m);
  quat[0] = q.w();
  quat[1] = q.x();
  quat[2] = q.y();
  quat[3] = q.z();
}

int polarRotationIterative(const double F[9], double quat[4], double R[9], int maxIterations,
                           double tolerance) {
  Eigen::Quaterniond q(quat[0], quat[1], quat[2], quat[3]);
  q.normalize();
  if (!allFinite(F, 9)) {
    store(q.toRotationMatrix(), R);
    return -1;
  }
  const Eigen::Map<const Mat3> f(F);
  if (f.determinant() <= 0.0) {
    // Inverted or flat: the basin of Irving's rotation shrinks to nothing as σ2 − σ3 -> 0
    // (the Hessian eigenvalue σ2 − σ3 vanishes), and measured 0.5 rad warm starts ended on
    // a wrong stationary point in up to half of such cases. Inversions are rare, so the
    // SVD costs nothing on average here.
    polarRotationSvd(F, R);
    quaternionFromRotation(R, quat);
    return 0;
  }
  int iteration = 0;
  Eigen::Matrix3d r = q.toRotationMatrix();
  for (; iteration < maxIterations; ++iteration) {
    // g = Σ r_i × f_i is the gradient of tr(Rᵀ F) for a world-frame rotation exp([δ]) R;
    // its Hessian is −(tr(B) I − sym(B)) with B = F Rᵀ. Müller et al. step by g / |tr(B)|,
    // i.e. they approximate that matrix by tr(B) I, which near the optimum (sym(B) ≈ the
    // stretch) under-steps by a factor ≈ 2/3: linear convergence, about 3x error reduction
    // per iteration. We take the Newton step when the matrix is positive definite (always
    // near the optimum, inverted elements included, since Irving's choice puts −σ3 on the
    // smallest singular value) and fall back to their step otherwise (far from the optimum,
    // or a rank-deficient F), where it is a safe ascent direction.
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) g += r.col(i).cross(f.col(i));
    const Eigen::Matrix3d b = f * r.transpose();
    const double trace = b.trace();
    const Eigen::Matrix3d hessian =
        trace * Eigen::Matrix3d::Identity() - 0.5 * (b + b.transpose());
    const Eigen::LLT<Eigen::Matrix3d> llt(hessian);
    Eigen::Vector3d omega;
    bool newton = false;
    if (llt.info() == Eigen::Success) {
      omega = llt.solve(g);
      // A nearly singular Hessian (rank-deficient F) gives a huge, meaningless step.
      newton = omega.allFinite() && omega.norm() < 1.0;
    }
    // The 1e-9 only prevents a division by zero (tr = 0 happens for F = 0).
    if (!newton) omega = g / (std::fabs(trace) + 1e-9);
    const double angle = omega.norm();
    if (angle < tolerance) break;
    q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle)) * q;
    q.normalize();
    r = q.toRotationMatrix();
  }
  quat[0] = q.w();
  quat[1] = q.x();
  quat[2] = q.y();
  quat[3] = q.z();
  store(r, R);
  return iteration;
}

}  // namespace vp
