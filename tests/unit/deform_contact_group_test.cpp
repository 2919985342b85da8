// Deformables that touch solve as one system (deform/contact_groups.h, contact_group_solve.h):
// which bodies join a group and which contacts are coupled, and the coupled spring's terms
// between nodes (addPairCouplingProduct) with its diagonal blocks make the spring's whole
// Hessian D c cᵀ, c = (1, −w_0, −w_1, −w_2): the node feels D u and corner i −w_i D u, u the
// node's velocity relative to the triangle's point.
#include <gtest/gtest.h>

#include <random>

#include "deform/contact_groups.h"
#include "deform/pair_contact_terms.h"

namespace vp {
namespace {

PairContact contact(int32_t nodeBody, int32_t triangleBody) {
  PairContact p;
  p.nodeBody = nodeBody;
  p.node = 0;
  p.triangleBody = triangleBody;
  p.triangleNodes = {1, 2, 3};
  return p;
}

TEST(ContactGroups, BodiesSteppingTogetherJoinAndTheirContactsAreCoupled) {
  // 0–1 touch; 2 touches itself; 1 touches 3, which does not step this frame; 4 touches 0
  // but steps a longer dt (a lowered rate); 5 solves on the device.
  std::vector<ContactGroupCandidate> bodies(6, ContactGroupCandidate{true, true, 1.0 / 60.0});
  bodies[3].steps = false;
  bodies[4].dt = 2.0 / 60.0;
  bodies[5].onCpu = false;
  std::vector<PairContact> pairs{contact(0, 1), contact(2, 2), contact(1, 3), contact(4, 0), contact(5, 5),
                                 contact(1, 0)};
  const std::vector<int> order{2, 1, 0, 4, 5};  // as served
  const std::vector<std::vector<int>> groups = formContactGroups(order, bodies, &pairs);
  ASSERT_EQ(groups.size(), 4u);
  EXPECT_EQ(groups[0], std::vector<int>({2}));
  EXPECT_EQ(groups[1], std::vector<int>({1, 0}));  // ordered as served, named by the first
  EXPECT_EQ(groups[2], std::vector<int>({4}));
  EXPECT_EQ(groups[3], std::vector<int>({5}));
  const std::vector<bool> coupled{true, true, false, false, false, true};
  for (size_t c = 0; c < pairs.size(); ++c) EXPECT_EQ(pairs[c].coupled, coupled[c]) << "contact " << c;
}

Vec3 at(const std::vector<double>& v, int64_t offset, int32_t node) {
  return Vec3(v[offset + 3 * node], v[offset + 3 * node + 1], v[offset + 3 * node + 2]);
}

// Node 0 of body 0 on the triangle (1, 2, 3) of body 1, whose 4 nodes come after body 0's 4 in
// the group's vector; with `self`, on the triangle (1, 2, 3) of its own body of 8 nodes.
void expectWholeHessian(bool sliding, bool self) {
  PairContact p = contact(0, self ? 0 : 1);
  p.coupled = true;
  p.weights = Vec3(0.2, 0.3, 0.5);
  p.normal = Vec3(1.0, 2.0, -0.5).normalized();
  p.reducedMass = 0.7;
  p.state.sliding = sliding ? 1 : 0;
  const std::vector<int64_t> offsets{0, self ? -1 : 12};
  const int64_t triangleOffset = self ? 0 : 12;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> x(24), y(24, 0.0);
  for (double& value : x) value = uniform(random);
  addPairCouplingProduct({p}, offsets, x.data(), y.data());

  const Mat3 N = p.normal * p.normal.transpose();
  const Mat3 D = p.springH2k() * (sliding ? N : Mat3::Identity());
  // The diagonal blocks addPairContactStiffness puts in the bodies' matrices.
  Vec3 node = at(y, 0, 0) + D * at(x, 0, 0);
  Vec3 u = at(x, 0, 0);
  for (int i = 0; i < 3; ++i) u -= p.weights[i] * at(x, triangleOffset, p.triangleNodes[i]);
  EXPECT_LT((node - D * u).norm(), 1e-12 * (D * u).norm());
  for (int i = 0; i < 3; ++i) {
    const int32_t corner = p.triangleNodes[i];
    const Vec3 whole =
        at(y, triangleOffset, corner) + p.weights[i] * p.weights[i] * D * at(x, triangleOffset, corner);
    EXPECT_LT((whole + p.weights[i] * D * u).norm(), 1e-12 * (D * u).norm()) << "corner " << i;
  }
  // Nodes on no contact get nothing from the product.
  if (!self) {
    for (int32_t n = 1; n < 4; ++n) EXPECT_EQ(at(y, 0, n), Vec3::Zero());
    EXPECT_EQ(at(y, 12, 0), Vec3::Zero());
  }
  if (self) {
    for (int32_t n = 4; n < 8; ++n) EXPECT_EQ(at(y, 0, n), Vec3::Zero());
  }
}

TEST(ContactGroups, ACoupledSpringsTermsMakeItsWholeHessianSticking) { expectWholeHessian(false, false); }
TEST(ContactGroups, ACoupledSpringsTermsMakeItsWholeHessianSliding) { expectWholeHessian(true, false); }
TEST(ContactGroups, ACoupledSelfContactsTermsMakeItsWholeHessian) { expectWholeHessian(false, true); }

// Node 0 of body 0 (4 nodes) against a rigid body, pair body 1, whose six velocities (linear,
// angular) follow in the group's vector. The spring acts on the relative velocity
// u = v − (V + Ω × arm): the node's rows of A x hold D u, the rigid body's the generalized force
// of −D u at the arm, and its right-hand side that of −c, c the spring's known impulse.
void expectRigidTerms(bool sliding) {
  const double h = 1.0 / 60.0;
  PairContact p;
  p.nodeBody = 0;
  p.node = 2;
  p.triangleBody = 1;
  p.rigidSide = true;
  p.coupled = true;
  p.weights = Vec3(1.0, 0.0, 0.0);
  p.arm = Vec3(0.3, -0.2, 0.1);
  p.normal = Vec3(0.5, 1.0, 0.2).normalized();
  p.reducedMass = 0.7;
  p.gap = 0.001;
  p.rest = 0.004;
  p.state.sliding = sliding ? 1 : 0;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> x(18), y(18, 0.0);
  for (double& value : x) value = uniform(random);
  addPairCouplingProduct({p}, {0, 12}, x.data(), y.data());
  Mat6 block = Mat6::Zero();
  Vec6 rhs = Vec6::Zero();
  addRigidContactTerms({p}, 1, h, &block, &rhs);

  const Mat3 D = p.springH2k() * (sliding ? Mat3(p.normal * p.normal.transpose()) : Mat3::Identity());
  const Vec3 V(x[12], x[13], x[14]), W(x[15], x[16], x[17]);
  const Vec3 u = at(x, 0, p.node) - (V + W.cross(p.arm));
  const Vec3 Du = D * u;
  EXPECT_LT((at(y, 0, p.node) + D * at(x, 0, p.node) - Du).norm(), 1e-12 * Du.norm());
  const Vec6 rigidRows = Eigen::Map<const Vec6>(&y[12]) + block * Eigen::Map<const Vec6>(&x[12]);
  EXPECT_LT((rigidRows.head<3>() + Du).norm(), 1e-12 * Du.norm());
  EXPECT_LT((rigidRows.tail<3>() + p.arm.cross(Du)).norm(), 1e-12 * Du.norm());
  for (int32_t n : {0, 1, 3}) EXPECT_EQ(at(y, 0, n), Vec3::Zero());
  // The known impulse pushes the node out to the rest gap: h k (rest − gap) along the normal.
  const Vec3 known = p.springH2k() / h * (p.rest - p.gap) * p.normal;
  EXPECT_LT((rhs.head<3>() + known).norm(), 1e-12 * known.norm());
  EXPECT_LT((rhs.tail<3>() + p.arm.cross(known)).norm(), 1e-12 * known.norm());
  // The impulse on the node at given velocities: c − D u.
  Array<double> nodes(x.begin(), x.begin() + 12), rigid(x.begin() + 12, x.end());
  const Vec3 impulse = coupledNodeImpulse(p, h, {&nodes, &rigid});
  EXPECT_LT((impulse - (known - Du)).norm(), 1e-12 * (known.norm() + Du.norm()));
}

TEST(ContactGroups, ARigidContactsTermsAreItsSpringOnTheRelativeVelocitySticking) { expectRigidTerms(false); }
TEST(ContactGroups, ARigidContactsTermsAreItsSpringOnTheRelativeVelocitySliding) { expectRigidTerms(true); }

TEST(ContactGroups, UncoupledContactsAndBodiesOutsideTheGroupAddNothing) {
  PairContact uncoupled = contact(0, 1);
  uncoupled.weights = Vec3(0.2, 0.3, 0.5);
  uncoupled.reducedMass = 1.0;
  PairContact outside = uncoupled;
  outside.coupled = true;
  outside.triangleBody = 2;  // body 2 is not in the group
  std::vector<double> x(24, 1.0), y(24, 0.0);
  addPairCouplingProduct({uncoupled, outside}, {0, 12, -1}, x.data(), y.data());
  for (double value : y) EXPECT_EQ(value, 0.0);
}

}  // namespace
}  // namespace vp
