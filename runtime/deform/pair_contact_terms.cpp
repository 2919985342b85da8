#include "deform/pair_contact_terms.h"

#include <algorithm>

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

// visit(node, D, c) for each node of `body` on contact p, over a step of h.
template <class Visit>
void visitTerms(const PairContact& p, int32_t body, double h, const Visit& visit) {
  const double K2 = kPairContactStiffness * p.reducedMass;  // h² k
  const double K1 = K2 / h;                                 // h k
  const Mat3 N = p.normal * p.normal.transpose();
  const bool slides = p.state.sliding != 0;
  const Mat3 D = slides ? Mat3(K2 * N) : Mat3(K2 * Mat3::Identity());
  const Vec3 friction = slides ? Vec3(p.friction * p.state.lastNormalImpulse * slipDirection(p)) : Vec3::Zero();
  const Vec3 push = K1 * (p.rest - p.gap) * p.normal;
  auto along = [&](const Vec3& v) { return slides ? Vec3(N * v) : v; };
  if (p.nodeBody == body) visit(p.node, D, Vec3(push - (slides ? Vec3::Zero() : Vec3(K1 * p.state.stick)) +
                                                along(K2 * p.triangleVelocity()) - friction));
  if (p.triangleBody != body) return;
  for (int i = 0; i < 3; ++i) {
    const double w = p.weights[i];
    Vec3 others = Vec3::Zero();
    for (int j = 0; j < 3; ++j)
      if (j != i) others += p.weights[j] * p.triangleVelocities[j];
    const Vec3 spring = push - (slides ? Vec3::Zero() : Vec3(K1 * p.state.stick)) + along(K2 * (others - p.nodeVelocity));
    visit(p.triangleNodes[i], Mat3(w * w * D), Vec3(-w * (spring - friction)));
  }
}

bool touches(const PairContact& p, int32_t body) { return p.nodeBody == body || p.triangleBody == body; }

}  // namespace

void addPairContactStiffness(const std::vector<PairContact>& pairs, int32_t body, double h,
                             BlockSparseMatrix<double>* matrix) {
  for (const PairContact& p : pairs) {
    if (!touches(p, body)) continue;
    visitTerms(p, body, h, [&](int32_t node, const Mat3& D, const Vec3&) {
      double* block = &matrix->values[9 * static_cast<int64_t>(matrix->diagonal[node])];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) block[3 * r + c] += D(r, c);
    });
  }
}

void addPairContactRhs(const std::vector<PairContact>& pairs, int32_t body, double h, Array<double>* rhs) {
  for (const PairContact& p : pairs) {
    if (!touches(p, body)) continue;
    visitTerms(p, body, h, [&](int32_t node, const Mat3&, const Vec3& c) {
      for (int k = 0; k < 3; ++k) (*rhs)[3 * node + k] += c[k];
    });
  }
}

double pairContactWork(const std::vector<PairContact>& pairs, int32_t body, double h, const Array<double>& vNext) {
  double work = 0.0;
  for (const PairContact& p : pairs) {
    if (!touches(p, body)) continue;
    visitTerms(p, body, h, [&](int32_t node, const Mat3& D, const Vec3& c) {
      const Vec3 v = nodeVector(vNext, node);
      work += (c - D * v).dot(v);
    });
  }
  return work;
}

void updatePairFriction(const std::vector<PairContact>& pairs, int32_t body, double h, const Array<double>& vNext,
                        Array<PairFriction>* friction) {
  std::fill(friction->begin(), friction->end(), PairFriction());
  for (const PairContact& p : pairs) {
    if (p.nodeBody != body) continue;
    const Vec3 v = nodeVector(vNext, p.node);
    Vec3 impulse = Vec3::Zero();
    PairContact nodeOnly = p;
    nodeOnly.triangleBody = -1;  // only the node's own term
    visitTerms(nodeOnly, body, h, [&](int32_t, const Mat3& D, const Vec3& c) { impulse = c - D * v; });
    const double jn = impulse.dot(p.normal);
    if (!(jn > 0.0)) continue;
    PairFriction& f = (*friction)[p.node];
    f.otherBody = p.triangleBody;
    f.lastNormalImpulse = jn;
    Vec3 slip = v - p.triangleVelocity();
    slip -= slip.dot(p.normal) * p.normal;
    if (p.state.sliding) {
      // Slid: sticks again once the slip has stopped or turned against the friction.
      const bool stopped = slip.norm() < kPairSlipSpeed || slip.dot(slipDirection(p)) <= 0.0;
      f.sliding = stopped ? 0 : 1;
      continue;
    }
    const Vec3 stick = p.state.stick + h * slip;
    const double K1 = kPairContactStiffness * p.reducedMass / h;
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
