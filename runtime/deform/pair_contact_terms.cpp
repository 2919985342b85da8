#include "deform/pair_contact_terms.h"

#include <algorithm>
#include <array>
#include <utility>

namespace vp {
namespace {

Vec3 nodeVector(const Array<double>& a, int32_t i) { return Vec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]); }

// The direction kinetic friction opposes: the node's slip over the triangle at the frame's start.
Vec3 slipDirection(const PairContact& p) {
  const Vec3 slip = p.startSlip();
  const double s = slip.norm();
  return s > 0.0 ? Vec3(slip / s) : Vec3::Zero();
}

// The spring of contact p over a step of h: the impulse on the node is known − D u, with u
// the node's velocity relative to the triangle's point (−w_i times it on triangle node i).
struct Spring {
  Mat3 D = Mat3::Zero();
  Vec3 known = Vec3::Zero();  // the push to the rest gap, the stuck stretch and kinetic friction
  Vec3 nodeImpulse(const Vec3& vNode, const Vec3& vPoint) const { return known - D * (vNode - vPoint); }
};

// h² times the spring's stiffness matrix: along the normal only while the contact slides.
Mat3 springMatrix(const PairContact& p) {
  const double K2 = p.springH2k();
  return p.state.sliding ? Mat3(K2 * p.normal * p.normal.transpose()) : Mat3(K2 * Mat3::Identity());
}

Spring spring(const PairContact& p, double h) {
  const double K1 = p.springH2k() / h;  // h k
  const bool slides = p.state.sliding != 0;
  Spring s;
  s.D = springMatrix(p);
  const Vec3 friction = slides ? Vec3(p.friction * p.state.lastNormalImpulse * slipDirection(p)) : Vec3::Zero();
  s.known = K1 * (p.rest - p.gap) * p.normal - (slides ? Vec3::Zero() : Vec3(h * p.state.stick)) - friction;
  return s;
}

// One node's share of a contact in its body's step: the impulse on it is c − D v'.
struct Term {
  int32_t node = -1;
  Mat3 D = Mat3::Zero();
  Vec3 c = Vec3::Zero();
  Vec3 impulse(const Array<double>& vNext) const { return c - D * nodeVector(vNext, node); }
};

// visit(term) for each node of `body` on contact p, over a step of h: its diagonal share. An
// uncoupled contact's other side, and the triangle's other corners, are at their frame-start
// velocities in c: the corners' coupling w_i w_j k is left out of the matrix (with it, the
// stack of two jellies did not come to rest; docs/choices.md). A coupled contact's are
// unknowns of the same solve (addPairCouplingProduct).
template <class Visit>
void visitTerms(const PairContact& p, int32_t body, double h, const Visit& visit) {
  const Spring s = spring(p, h);
  if (p.nodeBody == body)
    visit(Term{p.node, s.D, p.coupled ? s.known : Vec3(s.known + s.D * p.triangleVelocity())});
  if (p.triangleBody != body) return;
  for (int i = 0; i < 3; ++i) {
    const double w = p.weights[i];
    Vec3 others = Vec3::Zero();
    for (int j = 0; j < 3; ++j)
      if (j != i) others += p.weights[j] * p.triangleVelocities[j];
    // Minus the node's impulse, with the point's velocity w v'_i + others.
    const Vec3 nodeImpulse = p.coupled ? s.known : Vec3(s.known + s.D * (others - p.nodeVelocity));
    visit(Term{p.triangleNodes[i], w * w * s.D, -w * nodeImpulse});
  }
}

// The rigid side's point velocity is V + Ω × arm, so the contact's relative velocity is
// v − (V + Ω × arm) = v + J u with u = (V, Ω) and J = [−I, [arm]×].
Eigen::Matrix<double, 3, 6> rigidJacobian(const Vec3& arm) {
  Eigen::Matrix<double, 3, 6> J;
  J.leftCols<3>() = -Mat3::Identity();
  J.rightCols<3>() << 0.0, -arm.z(), arm.y(), arm.z(), 0.0, -arm.x(), -arm.y(), arm.x(), 0.0;
  return J;
}

Vec6 sixVector(const double* x) { return Eigen::Map<const Vec6>(x); }

// A coupled contact's node velocity and its other side's point's, from the solved velocities.
std::pair<Vec3, Vec3> solvedVelocities(const PairContact& p, const PairVelocities& solved) {
  const Array<double>& t = *solved[p.triangleBody];
  const Vec3 node = p.rigidNode ? Vec3(-rigidJacobian(p.arm) * sixVector(solved[p.nodeBody]->data()))
                                : nodeVector(*solved[p.nodeBody], p.node);
  if (p.rigidSide) return {node, -rigidJacobian(p.arm) * sixVector(t.data())};
  Vec3 point = Vec3::Zero();
  for (int i = 0; i < 3; ++i) point += p.weights[i] * nodeVector(t, p.triangleNodes[i]);
  return {node, point};
}

// The friction state contact p leaves for the next step, from its node's velocity v and the
// triangle point's; false when its spring pulled (the state starts afresh).
bool nextFriction(const PairContact& p, double h, const Vec3& v, const Vec3& point, PairFriction* f) {
  const Vec3 impulse = spring(p, h).nodeImpulse(v, point);
  const double jn = impulse.dot(p.normal);
  if (!(jn > 0.0)) return false;
  f->other = p.triangleBodyId;
  f->lastNormalImpulse = jn;
  Vec3 slip = v - point;
  slip -= slip.dot(p.normal) * p.normal;
  const double k = p.springH2k() / (h * h);
  if (p.state.sliding) {
    // Slid: sticks again once the slip has stopped or turned against the friction, its
    // spring holding the friction it had.
    const bool stopped = slip.norm() < kPairSlipSpeed || slip.dot(slipDirection(p)) <= 0.0;
    f->sliding = stopped ? 0 : 1;
    if (stopped) f->stick = p.friction * jn * slipDirection(p) / h;
    return true;
  }
  const Vec3 stick = p.state.stick + k * h * slip;  // the spring's force after the step's slip
  const double cone = p.friction * jn;
  if (h * stick.norm() > cone) {
    f->sliding = 1;
    f->stick = stick * (cone / (h * stick.norm()));
  } else {
    f->stick = stick;
  }
  return true;
}

bool touches(const PairContact& p, int32_t body) { return p.nodeBody == body || p.triangleBody == body; }

}  // namespace

void addPairContactStiffness(const std::vector<PairContact>& pairs, int32_t body, double h,
                             BlockSparseMatrix<double>* matrix) {
  for (const PairContact& p : pairs) {
    if (!touches(p, body)) continue;
    visitTerms(p, body, h, [&](const Term& t) {
      double* block = &matrix->values[9 * static_cast<int64_t>(matrix->diagonal[t.node])];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) block[3 * r + c] += t.D(r, c);
    });
  }
}

void addPairContactRhs(const std::vector<PairContact>& pairs, int32_t body, double h, Array<double>* rhs) {
  for (const PairContact& p : pairs) {
    if (!touches(p, body)) continue;
    visitTerms(p, body, h, [&](const Term& t) {
      for (int k = 0; k < 3; ++k) (*rhs)[3 * t.node + k] += t.c[k];
    });
  }
}

Vec3 pairContactMismatch(const PairContact& p, double nodeH, const Array<double>& nodeV, double triangleH,
                         const Array<double>& triangleV) {
  Vec3 sum = Vec3::Zero();
  PairContact side = p;
  if (nodeH > 0.0) {
    side.nodeBody = 0, side.triangleBody = -1;
    visitTerms(side, 0, nodeH, [&](const Term& t) { sum += t.impulse(nodeV); });
  }
  if (triangleH > 0.0) {
    side.nodeBody = -1, side.triangleBody = 0;
    visitTerms(side, 0, triangleH, [&](const Term& t) { sum += t.impulse(triangleV); });
  }
  return sum;
}

double pairContactWork(const std::vector<PairContact>& pairs, int32_t body, double h, const Array<double>& vNext,
                       const PairVelocities& solved) {
  double work = 0.0;
  for (const PairContact& p : pairs) {
    if (!touches(p, body)) continue;
    if (p.coupled) {
      const auto [vNode, vPoint] = solvedVelocities(p, solved);
      const Vec3 impulse = spring(p, h).nodeImpulse(vNode, vPoint);
      if (p.nodeBody == body) work += impulse.dot(vNode);
      if (p.triangleBody == body) work -= impulse.dot(vPoint);
      continue;
    }
    visitTerms(p, body, h, [&](const Term& t) { work += t.impulse(vNext).dot(nodeVector(vNext, t.node)); });
  }
  return work;
}

void updatePairFriction(const std::vector<PairContact>& pairs, int32_t body, double h, const Array<double>& vNext,
                        const PairVelocities& solved, Array<PairFriction>* friction,
                        Array<CornerFriction>* cornerFriction) {
  std::fill(friction->begin(), friction->end(), PairFriction());
  cornerFriction->clear();
  for (const PairContact& p : pairs) {
    // A rigid corner's contact is always coupled: its body is solved with the deformable.
    const bool node = p.nodeBody == body && !p.attachment, corner = p.rigidNode && p.coupled && p.triangleBody == body;
    if (!node && !corner) continue;
    // The node's velocity and the triangle point's, as the node's side of the spring saw them.
    const auto [v, point] = p.coupled ? solvedVelocities(p, solved)
                                      : std::pair<Vec3, Vec3>(nodeVector(vNext, p.node), p.triangleVelocity());
    PairFriction f;
    if (!nextFriction(p, h, v, point, &f)) continue;
    if (node) (*friction)[p.node] = f;
    else cornerFriction->push_back(CornerFriction{p.nodeBodyId, p.node, f});
  }
}

Vec3 coupledNodeImpulse(const PairContact& p, double h, const PairVelocities& solved) {
  const auto [vNode, vPoint] = solvedVelocities(p, solved);
  return spring(p, h).nodeImpulse(vNode, vPoint);
}

void addRigidContactTerms(const std::vector<PairContact>& pairs, int32_t body, double h, Mat6* block, Vec6* rhs) {
  for (const PairContact& p : pairs) {
    const bool triangleSide = p.rigidSide && p.triangleBody == body, nodeSide = p.rigidNode && p.nodeBody == body;
    if (!triangleSide && !nodeSide) continue;
    // On the triangle side the rigid body takes −P at the point: J^T P = J^T c − J^T D (v + J u).
    // On the node side, where the node's velocity is −J u, it takes P: −J^T P = −J^T c − J^T D
    // (J u + v_point).
    const Eigen::Matrix<double, 3, 6> J = rigidJacobian(p.arm);
    const Spring s = spring(p, h);
    *block += J.transpose() * s.D * J;
    *rhs += (triangleSide ? 1.0 : -1.0) * (J.transpose() * s.known);
  }
}

void addPairCouplingProduct(const std::vector<PairContact>& pairs, const std::vector<int64_t>& offsets,
                            const double* x, double* y) {
  auto member = [&](int32_t body) { return body < static_cast<int32_t>(offsets.size()) && offsets[body] >= 0; };
  for (const PairContact& p : pairs) {
    if (!p.coupled || !member(p.nodeBody) || !member(p.triangleBody)) continue;
    const Mat3 D = springMatrix(p);
    if (p.rigidNode) {
      // The spring's Hessian is c^T D c with c = (−J, −w_0 I, −w_1 I, −w_2 I): the blocks
      // w_i J^T D (the rigid body's row), w_i D J and w_i w_j D (corner i's).
      const Eigen::Matrix<double, 3, 6> J = rigidJacobian(p.arm);
      const int64_t r = offsets[p.nodeBody];
      int64_t at[3];  // the corners' offsets
      Vec3 corner[3];
      for (int i = 0; i < 3; ++i) {
        at[i] = offsets[p.triangleBody] + 3 * static_cast<int64_t>(p.triangleNodes[i]);
        corner[i] = Eigen::Map<const Vec3>(x + at[i]);
      }
      const Vec3 rigidPart = D * (J * sixVector(x + r));
      Eigen::Map<Vec6>(y + r) +=
          J.transpose() * (D * (p.weights[0] * corner[0] + p.weights[1] * corner[1] + p.weights[2] * corner[2]));
      for (int i = 0; i < 3; ++i) {
        Vec3 others = Vec3::Zero();
        for (int j = 0; j < 3; ++j)
          if (j != i) others += p.weights[j] * corner[j];
        Eigen::Map<Vec3>(y + at[i]) += p.weights[i] * (rigidPart + D * others);
      }
      continue;
    }
    if (p.rigidSide) {
      // The blocks D J (the node's row) and J^T D (the rigid body's).
      const Eigen::Matrix<double, 3, 6> J = rigidJacobian(p.arm);
      const int64_t n = offsets[p.nodeBody] + 3 * static_cast<int64_t>(p.node), r = offsets[p.triangleBody];
      Eigen::Map<Vec3>(y + n) += D * (J * sixVector(x + r));
      Eigen::Map<Vec6>(y + r) += J.transpose() * (D * Eigen::Map<const Vec3>(x + n));
      continue;
    }
    const double* xs[4];
    double* ys[4];
    xs[0] = x + offsets[p.nodeBody] + 3 * static_cast<int64_t>(p.node);
    ys[0] = y + offsets[p.nodeBody] + 3 * static_cast<int64_t>(p.node);
    for (int i = 0; i < 3; ++i) {
      xs[i + 1] = x + offsets[p.triangleBody] + 3 * static_cast<int64_t>(p.triangleNodes[i]);
      ys[i + 1] = y + offsets[p.triangleBody] + 3 * static_cast<int64_t>(p.triangleNodes[i]);
    }
    // The spring's Hessian is D times c c^T with c = (1, −w_0, −w_1, −w_2); its diagonal blocks
    // are in the bodies' matrices (addPairContactStiffness), the rest is applied here.
    const double c[4] = {1.0, -p.weights[0], -p.weights[1], -p.weights[2]};
    for (int a = 0; a < 4; ++a) {
      Vec3 sum = Vec3::Zero();
      for (int b = 0; b < 4; ++b)
        if (b != a) sum += c[b] * Vec3(xs[b][0], xs[b][1], xs[b][2]);
      const Vec3 add = c[a] * (D * sum);
      for (int k = 0; k < 3; ++k) ys[a][k] += add[k];
    }
  }
}

}  // namespace vp
