#include "deform/rotating_position_update.h"

#include <Eigen/Geometry>

#include "deform/rigid_view.h"

namespace vp {
namespace {
constexpr int kMidpointIterations = 4;
}
}  // namespace vp

namespace vp {
namespace {

Eigen::Matrix3d turnBy(const Vec3& spin, double h) {
  const double angle = spin.norm() * h;
  if (!(angle > 0.0)) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, spin / spin.norm()).toRotationMatrix();
}

// The turn over the step about the spin at its middle: the spin the angular momentum has
// about the inertia turned by half of it (the implicit midpoint rule, a fixed point reached
// in a few iterations while w h is below a radian). Turned about the start's spin instead, a
// free body whose spin is not along a principal axis gains kinetic energy every step.
Eigen::Matrix3d midpointTurn(const RigidView& body, Vec3 spin, double h) {
  for (int iteration = 0; iteration < kMidpointIterations; ++iteration) {
    const Eigen::Matrix3d half = turnBy(spin, 0.5 * h);
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(half * body.inertia * half.transpose());
    if (ldlt.info() != Eigen::Success) break;
    spin = ldlt.solve(body.angularMomentum);
  }
  return turnBy(spin, h);
}

}  // namespace

void moveRotatingBody(const Array<double>& mass, double h, const Array<double>& vSolved, Array<double>* x,
                      Array<double>* v) {
  const RigidView body(*x, &vSolved, mass);
  const Vec3 spin = body.solveInertia(body.angularMomentum);
  if (!(body.mass > 0.0) || !(spin.norm() * h > 0.0)) return moveAlongStraightLines(h, vSolved, x, v);
  const Vec3 velocity = body.momentum / body.mass;
  const Eigen::Matrix3d turn = midpointTurn(body, spin, h);
  v->resize(vSolved.size());
  for (size_t i = 0; i < mass.size(); ++i) {
    const Vec3 r = RigidView::at(*x, i) - body.centre, vi = RigidView::at(vSolved, i);
    const Vec3 rest = vi - velocity - spin.cross(r);
    const Vec3 xNew = body.centre + h * velocity + turn * (r + h * rest);
    const Vec3 vNew = velocity + turn * (vi - velocity);
    for (int k = 0; k < 3; ++k) {
      (*x)[3 * i + k] = xNew[k];
      (*v)[3 * i + k] = vNew[k];
    }
  }
  // Turning the velocities turns their angular momentum about the centre with them, which is
  // conserved only where it lies along the spin: a spin about the new inertia gives it back.
  const RigidView turned(*x, v, mass);
  const Vec3 correction = turned.solveInertia(body.angularMomentum - turned.angularMomentum);
  for (size_t i = 0; i < mass.size(); ++i) {
    const Vec3 dv = correction.cross(RigidView::at(*x, i) - turned.centre);
    for (int k = 0; k < 3; ++k) (*v)[3 * i + k] += dv[k];
  }
}

void moveAlongStraightLines(double h, const Array<double>& vSolved, Array<double>* x, Array<double>* v) {
  v->resize(vSolved.size());
  for (size_t i = 0; i < x->size(); ++i) {
    (*v)[i] = vSolved[i];
    (*x)[i] += h * vSolved[i];
  }
}

}  // namespace vp
