#include "deform/rotating_position_update.h"

#include <Eigen/Geometry>
#include <cmath>

#include "deform/rigid_view.h"

namespace vp {
namespace {

// The rotation is taken in sub-turns of at most this angle, each by the implicit midpoint
// rule in kMidpointIterations fixed-point iterations, which converge while the sub-turn is
// well below a radian (their error shrinks by about the sub-turn each).
constexpr double kMaxSubTurn = 0.25;
constexpr int kMidpointIterations = 4;
// A spin that needs more sub-turns than this over one step is no body's (the speed guard
// restores such a step): the straight lines take it.
constexpr int kMaxSubTurns = 64;

Eigen::Matrix3d turnBy(const Vec3& spin, double h) {
  const double angle = spin.norm() * h;
  if (!(angle > 0.0)) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, spin / spin.norm()).toRotationMatrix();
}

// The body's turn over h: in sub-turns, each about the spin at its middle, the spin the
// angular momentum has about the inertia turned by half of it (the implicit midpoint rule).
// Turned about each step's starting spin instead, a free body whose spin is not along a
// principal axis gains kinetic energy every step.
Eigen::Matrix3d bodyTurn(const RigidView& body, const Vec3& spin, double h, int subTurns) {
  const double part = h / subTurns;
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity(), inertia = body.inertia;
  Vec3 middle = spin;
  for (int s = 0; s < subTurns; ++s) {
    for (int iteration = 0; iteration < kMidpointIterations; ++iteration) {
      const Eigen::Matrix3d half = turnBy(middle, 0.5 * part);
      if (!RigidView::solve(half * inertia * half.transpose(), body.angularMomentum, &middle)) break;
    }
    const Eigen::Matrix3d step = turnBy(middle, part);
    turn = step * turn;
    inertia = step * inertia * step.transpose();
  }
  return turn;
}

}  // namespace

void moveRotatingBody(const Array<double>& mass, double h, const Array<double>& vSolved, Array<double>* x,
                      Array<double>* v) {
  const RigidView body(*x, &vSolved, mass);
  Vec3 spin = Vec3::Zero();
  if (!(body.mass > 0.0) || !RigidView::solve(body.inertia, body.angularMomentum, &spin))
    return moveAlongStraightLines(h, vSolved, x, v);
  const double angle = spin.norm() * h;
  if (!(angle > 0.0) || !(angle <= kMaxSubTurns * kMaxSubTurn)) return moveAlongStraightLines(h, vSolved, x, v);
  const Vec3 velocity = body.momentum / body.mass;
  const Eigen::Matrix3d turn = bodyTurn(body, spin, h, static_cast<int>(std::ceil(angle / kMaxSubTurn)));
  v->resize(vSolved.size());
  for (size_t i = 0; i < mass.size(); ++i) {
    const Vec3 r = RigidView::at(*x, i) - body.centre, rigid = spin.cross(r);
    const Vec3 rest = RigidView::at(vSolved, i) - velocity - rigid;
    const Vec3 xNew = body.centre + h * velocity + turn * r + h * rest;
    const Vec3 vNew = velocity + turn * (rigid + rest);
    for (int k = 0; k < 3; ++k) {
      (*x)[3 * i + k] = xNew[k];
      (*v)[3 * i + k] = vNew[k];
    }
  }
  // Turning the rigid velocities turned their angular momentum about the centre with them,
  // which is conserved only where it lies along the spin: a spin about the new inertia gives it
  // back.
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
