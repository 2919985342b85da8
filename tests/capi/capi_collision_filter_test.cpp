// Collision filters through the C ABI: defaults in the defs, get/set for each kind, and the
// rule at work (tests/unit/world_collision_filter_test.cpp checks it in every place it applies).
#include "capi_test_support.h"

namespace {

constexpr uint32_t kAll = 0xFFFFFFFFu;

void expectFilter(const vpCollisionFilter& f, uint32_t category, uint32_t mask) {
  EXPECT_EQ(f.categoryBits, category);
  EXPECT_EQ(f.maskBits, mask);
}

TEST(CApiCollisionFilter, DefaultsMeetEverything) {
  expectFilter(vpDefaultColliderDef().filter, 1, kAll);
  expectFilter(vpDefaultDeformableDef().filter, 1, kAll);
  expectFilter(vpDefaultFluidDef().filter, 1, kAll);
}

TEST(CApiCollisionFilter, ABallPassesThroughAGroundItDoesNotMeetUntilTheFilterChanges) {
  ScopedWorld w;
  vpColliderDef groundDef = vpDefaultColliderDef();
  groundDef.shape.type = vpShapeType_Plane;
  groundDef.filter = vpCollisionFilter{2, kAll};
  vpColliderId ground{}, ball{};
  ASSERT_VP_OK(vpColliderCreate(w.id, &groundDef, &ground));
  vpColliderDef ballDef = dynamicBall(3.0f);
  ballDef.filter = vpCollisionFilter{1, kAll & ~2u};
  ASSERT_VP_OK(vpColliderCreate(w.id, &ballDef, &ball));
  vpCollisionFilter read{};
  ASSERT_VP_OK(vpColliderGetCollisionFilter(ball, &read));
  expectFilter(read, 1, kAll & ~2u);
  for (int i = 0; i < 10; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  ASSERT_VP_OK(vpColliderSetCollisionFilter(ball, vpCollisionFilter{1, kAll}));
  for (int i = 0; i < 120; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  vpTransform pose{};
  ASSERT_VP_OK(vpColliderGetPose(ball, &pose));
  EXPECT_NEAR(pose.position.y, 0.5f, 0.01f);  // landed once they met
  ASSERT_VP_OK(vpColliderSetCollisionFilter(ground, vpCollisionFilter{0, 0}));
  for (int i = 0; i < 60; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  ASSERT_VP_OK(vpColliderGetPose(ball, &pose));
  EXPECT_LT(pose.position.y, -2.0f);  // the ground meets nothing now
}

TEST(CApiCollisionFilter, DeformableAndFluidFiltersReadBackWhatWasSet) {
  ScopedWorld w;
  static const float vertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const int32_t tet[4] = {0, 1, 2, 3};
  vpDeformableDef d = vpDefaultDeformableDef();
  d.vertices = vertices;
  d.vertexCount = 4;
  d.tets = tet;
  d.tetCount = 1;
  d.filter = vpCollisionFilter{4, 5};
  vpDeformableId jelly{};
  ASSERT_VP_OK(vpDeformableCreate(w.id, &d, &jelly));
  vpCollisionFilter read{};
  ASSERT_VP_OK(vpDeformableGetCollisionFilter(jelly, &read));
  expectFilter(read, 4, 5);
  ASSERT_VP_OK(vpDeformableSetCollisionFilter(jelly, vpCollisionFilter{kAll, 0}));
  ASSERT_VP_OK(vpDeformableGetCollisionFilter(jelly, &read));
  expectFilter(read, kAll, 0);

  vpFluidDef f = vpDefaultFluidDef();
  f.resolution[0] = f.resolution[1] = f.resolution[2] = 4;
  f.filter = vpCollisionFilter{8, 9};
  vpFluidId smoke{};
  ASSERT_VP_OK(vpFluidCreate(w.id, &f, &smoke));
  ASSERT_VP_OK(vpFluidGetCollisionFilter(smoke, &read));
  expectFilter(read, 8, 9);
  ASSERT_VP_OK(vpFluidSetCollisionFilter(smoke, vpCollisionFilter{16, 17}));
  ASSERT_VP_OK(vpFluidGetCollisionFilter(smoke, &read));
  expectFilter(read, 16, 17);
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
}

TEST(CApiCollisionFilter, NullOutputsAndStaleIdsAreRefused) {
  ScopedWorld w;
  vpColliderDef def = vpDefaultColliderDef();
  vpColliderId c{};
  ASSERT_VP_OK(vpColliderCreate(w.id, &def, &c));
  EXPECT_EQ(vpColliderGetCollisionFilter(c, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("outFilter is NULL")) << vpGetLastError();
  ASSERT_VP_OK(vpColliderDestroy(c));
  vpCollisionFilter read{};
  EXPECT_EQ(vpColliderGetCollisionFilter(c, &read), vpStatus_InvalidId);
  EXPECT_EQ(vpColliderSetCollisionFilter(c, vpCollisionFilter{1, 1}), vpStatus_InvalidId);
  EXPECT_EQ(vpDeformableSetCollisionFilter(vpDeformableId{}, vpCollisionFilter{1, 1}), vpStatus_InvalidId);
  EXPECT_EQ(vpFluidGetCollisionFilter(vpFluidId{}, &read), vpStatus_InvalidId);
}

}  // namespace
