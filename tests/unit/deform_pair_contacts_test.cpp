// Contact detection between deformables (deform/pair_contacts.h) on two single tets: a node
// at rest is found by a triangle that reaches it within the step, though the node's own search
// covers only its own motion (the triangle's box holds the triangle's), and a body's own
// neighbourhood never counts as self contact.
#include <gtest/gtest.h>

#include "deform/pair_contacts.h"

namespace vp {
namespace {

constexpr double kStep = 1.0 / 60.0;

// One linear tet as a contact body: corners x, every corner moving at v.
struct TetBody {
  Array<double> x, v, mass{1.0, 1.0, 1.0, 1.0};
  Array<int32_t> surfaceNodes{0, 1, 2, 3};
  Array<PairFriction> friction = Array<PairFriction>(4);
  ContactSurface surface;

  // Faces listed outward (counter-clockwise seen from outside) for corners whose fourth lies
  // on the far side of face (0, 2, 1).
  TetBody(const std::array<Vec3, 4>& corners, const Vec3& velocity) {
    SurfaceMesh boundary;
    for (const Vec3& c : corners) {
      boundary.vertices.push_back(c);
      for (int k = 0; k < 3; ++k) x.push_back(c[k]), v.push_back(velocity[k]);
    }
    boundary.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    surface.build(boundary, Array<int32_t>{0, 1, 2, 3}, Array<int32_t>{0, 1, 2, 3}, 4, 4);
  }

  PairContactBody body(double h, bool selfCollision) {
    surface.refit(x, v, h);
    PairContactBody b;
    b.x = &x;
    b.v = &v;
    b.mass = &mass;
    b.surfaceNodes = &surfaceNodes;
    b.surface = &surface;
    b.friction = &friction;
    b.rest = 0.01;
    b.depth = 0.05;
    b.selfCollision = selfCollision;
    return b;
  }
};

// A floor tet whose top face (0, 2, 1) lies in y = 0, its apex below.
TetBody floorTet(const Vec3& velocity) {
  return TetBody({Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(0, 0, 1), Vec3(0, -1, 0)}, velocity);
}

// A tet standing on its apex (node 0) `gap` above the floor tet's top face, at rest.
TetBody apexTet(double gap) {
  return TetBody({Vec3(0, gap, 0), Vec3(-1, gap + 1, 1), Vec3(1, gap + 1, 1), Vec3(0, gap + 1, -1)}, Vec3::Zero());
}

const PairContact* contactOfNode(const std::vector<PairContact>& contacts, int32_t body, int32_t node) {
  for (const PairContact& c : contacts)
    if (c.nodeBody == body && c.node == node) return &c;
  return nullptr;
}

TEST(PairContactDetection, ATriangleThatReachesARestingNodeWithinTheStepFindsIt) {
  // The floor rises at 6 m/s: within the step it moves 0.1 m, past the apex 0.08 m above it.
  // The apex's own search box (rest + depth = 0.06 m, no motion) does not reach the floor.
  const double gap = 0.08, speed = 6.0;
  TetBody apex = apexTet(gap), rising = floorTet(Vec3(0, speed, 0));
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  std::vector<PairContact> contacts;
  findPairContacts({apex.body(kStep, false), rising.body(kStep, false)}, {}, kStep, *tasks, &contacts);
  const PairContact* c = contactOfNode(contacts, 0, 0);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->triangleBody, 1);
  EXPECT_EQ(c->triangleNodes, (RefitBvh::Triangle{0, 2, 1}));
  EXPECT_NEAR(c->normal.y(), 1.0, 1e-15);
  EXPECT_NEAR(c->gap, gap, 1e-15);
  EXPECT_NEAR(c->predictedGap(kStep), gap - kStep * speed, 1e-15);

  // The same floor at rest is not touched within the step: predicted gap 0.08 > rest 0.01.
  TetBody still = floorTet(Vec3::Zero());
  findPairContacts({apex.body(kStep, false), still.body(kStep, false)}, {}, kStep, *tasks, &contacts);
  EXPECT_EQ(contactOfNode(contacts, 0, 0), nullptr);
}

TEST(PairContactDetection, ABodysOwnCornersAreNotSelfContacts) {
  // Every node of a lone tet lies on three of its own faces and next to the fourth's corners:
  // with self collision on there is still nothing to find.
  TetBody tet = floorTet(Vec3(0.3, -2.0, 0.1));
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  std::vector<PairContact> contacts;
  findPairContacts({tet.body(kStep, true)}, {}, kStep, *tasks, &contacts);
  EXPECT_TRUE(contacts.empty());
}

}  // namespace
}  // namespace vp
