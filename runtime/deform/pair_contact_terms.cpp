#include "deform/pair_contact_terms.h"

#include <algorithm>
#include <array>

namespace vp {
namespace {

Vec3 nodeVector(const Array<double>& a, int32_t i) { return Vec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]); }

// The direction kinetic friction opposes: the node's slip over the triangle at the frame's start.
Vec3 slipDirection(const PairContact& p) {
  Vec3 slip = p.nodeVelocity - p.triangleVelocity();
  slip -= slip.dot(p.normal) * p.normal;
  const double s = slip.norm();
  return s > 0.0 ? Vec3(slip / s) : Vec3::Zero();
}

// One node's share of a contact in its body's step: the impulse on it is c − D v'.
struct Term {
  int32_t node = -1;
  Mat3 D = Mat3::Zero();
  Vec3 c = Vec3::Zero();
  Vec3 impulse(const Array<double>& vNext) const { return c - D * nodeVector(vNext, node); }
};

// visit(term) for each node of `body` on contact p, over a step of h. The triangle's corners
// each take their weight's share with the other corners at their frame-start velocities: the
// corners' coupling w_i w_j k is left out of the matrix (with it, in the matrix, the stack of
// two jellies did not come to rest; docs/choices.md).
template <class Visit>
void visitTerms(const PairContact& p, int32_t body, double h, const Visit& visit) {
  const double K2 = kPairContactStiffness * p.reducedMass;  // h² k
  const double K1 = K2 / h;                                 // h k
  const Mat3 N = p.normal * p.normal.transpose();
  const bool slides = p.state.sliding != 0;
  const Mat3 D = slides ? Mat3(K2 * N) : Mat3(K2 * Mat3::Identity());
  const Vec3 friction = slides ? Vec3(p.friction * p.state.lastNormalImpulse * slipDirection(p)) : Vec3::Zero();
  // The spring's known part: the push to its rest gap and the stuck stretch.
  const Vec3 known = K1 * (p.rest - p.gap) * p.normal - (slides ? Vec3::Zero() : Vec3(K1 * p.state.stick));
  if (p.nodeBody == body) visit(Term{p.node, D, known + D * p.triangleVelocity() - friction});
  if (p.triangleBody != body) return;
  for (int i = 0; i < 3; ++i) {
    const double w = p.weights[i];
    Vec3 others = Vec3::Zero();
    for (int j = 0; j < 3; ++j)
      if (j != i) others += p.weights[j] * p.triangleVelocities[j];
    // Minus the node's impulse, with the point's velocity w v'_i + others.
    visit(Term{p.triangleNodes[i], w * w * D, -w * (known + D * (others - p.nodeVelocity) - friction)});
  }
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

double pairContactWork(const std::vector<PairContact>& pairs, int32_t body, double h, const Array<double>& vNext) {
  double work = 0.0;
  for (const PairContact& p : pairs) {
    if (!touches(p, body)) continue;
    visitTerms(p, body, h, [&](const Term& t) { work += t.impulse(vNext).dot(nodeVector(vNext, t.node)); });
  }
  return work;
}

void updatePairFriction(const std::vector<PairContact>& pairs, int32_t body, double h, const Array<double>& vNext,
                        Array<PairFriction>* friction) {
  std::fill(friction->begin(), friction->end(), PairFriction());
  for (const PairContact& p : pairs) {
    if (p.nodeBody != body) continue;
    const Vec3 v = nodeVector(vNext, p.node);
    PairContact nodeSide = p;
    nodeSide.triangleBody = -1;
    Vec3 impulse = Vec3::Zero();
    visitTerms(nodeSide, body, h, [&](const Term& t) { impulse = t.impulse(vNext); });
    const double jn = impulse.dot(p.normal);
    if (!(jn > 0.0)) continue;
    PairFriction& f = (*friction)[p.node];
    f.other = p.triangleBodyId;
    f.lastNormalImpulse = jn;
    Vec3 slip = v - p.triangleVelocity();
    slip -= slip.dot(p.normal) * p.normal;
    const double K1 = kPairContactStiffness * p.reducedMass / h;
    if (p.state.sliding) {
      // Slid: sticks again once the slip has stopped or turned against the friction, its
      // spring stretched to hold the friction it had.
      const bool stopped = slip.norm() < kPairSlipSpeed || slip.dot(slipDirection(p)) <= 0.0;
      f.sliding = stopped ? 0 : 1;
      if (stopped) f.stick = p.friction * jn * slipDirection(p) / K1;
      continue;
    }
    const Vec3 stick = p.state.stick + h * slip;
    const double cone = p.friction * jn;
    if (K1 * stick.norm() > cone) {
      f.sliding = 1;
      f.stick = stick * (cone / (K1 * stick.norm()));
    } else {
      f.stick = stick;
    }
  }
}

}  // namespace vp
