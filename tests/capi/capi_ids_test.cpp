// Ids: null, stale, destroyed, from a world whose slot was reused, of the wrong kind, and never
// issued twice.
#include <cstring>
#include <set>
#include <utility>

#include "capi_test_support.h"

namespace {

TEST(CApiIds, NullIdsAreErrorsNotCrashes) {
  vpWorldId nullWorld{};
  vpColliderId nullCollider{};
  EXPECT_TRUE(vpWorldIdIsNull(nullWorld));
  EXPECT_TRUE(vpColliderIdIsNull(nullCollider));
  EXPECT_EQ(vpWorldStep(nullWorld, 0.01f), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("world id (0, 0)"));
  EXPECT_EQ(vpWorldDestroy(nullWorld), vpStatus_InvalidId);
  vpTransform pose;
  EXPECT_EQ(vpColliderGetPose(nullCollider, &pose), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("collider id is null"));
  vpColliderDef def = vpDefaultColliderDef();
  vpColliderId out;
  EXPECT_EQ(vpColliderCreate(nullWorld, &def, &out), vpStatus_InvalidId);
}

TEST(CApiIds, GarbageIdsAreErrors) {
  ScopedWorld w;
  vpWorldId bogusWorld{999, 3};
  EXPECT_EQ(vpWorldStep(bogusWorld, 0.01f), vpStatus_InvalidId);
  vpColliderId bogus{12345, 1, w.id};
  vpTransform pose;
  EXPECT_EQ(vpColliderGetPose(bogus, &pose), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("collider id (12345, 1)"));
}

TEST(CApiIds, DestroyedColliderIdIsStale) {
  ScopedWorld w;
  vpColliderDef def = dynamicBall(1.0f);
  vpColliderId a, b;
  ASSERT_VP_OK(vpColliderCreate(w.id, &def, &a));
  ASSERT_VP_OK(vpColliderDestroy(a));
  EXPECT_EQ(vpColliderIsValid(a), vpStatus_InvalidId);
  EXPECT_EQ(vpColliderDestroy(a), vpStatus_InvalidId);
  ASSERT_VP_OK(vpColliderCreate(w.id, &def, &b));
  EXPECT_EQ(a.index1, b.index1);  // slot reused...
  EXPECT_EQ(vpColliderIsValid(a), vpStatus_InvalidId);  // ...but the old id stays dead
  EXPECT_VP_OK(vpColliderIsValid(b));
  vpVec3 v{1, 0, 0};
  EXPECT_EQ(vpColliderSetVelocity(a, v, v), vpStatus_InvalidId);
}

TEST(CApiIds, IdsFromADestroyedWorldDoNotResolveInItsSuccessor) {
  vpWorldDef def = vpDefaultWorldDef();
  vpWorldId first;
  ASSERT_VP_OK(vpWorldCreate(&def, &first));
  vpColliderDef ball = dynamicBall(1.0f);
  vpColliderId oldCollider;
  ASSERT_VP_OK(vpColliderCreate(first, &ball, &oldCollider));
  ASSERT_VP_OK(vpWorldDestroy(first));

  vpWorldId second;
  ASSERT_VP_OK(vpWorldCreate(&def, &second));
  EXPECT_EQ(second.index1, first.index1);  // same slot
  vpColliderId newCollider;
  ASSERT_VP_OK(vpColliderCreate(second, &ball, &newCollider));
  EXPECT_EQ(newCollider.index1, oldCollider.index1);
  EXPECT_EQ(newCollider.generation, oldCollider.generation);  // only the world differs

  vpTransform pose;
  EXPECT_EQ(vpColliderGetPose(oldCollider, &pose), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("stale or null"));
  EXPECT_EQ(vpWorldStep(first, 0.01f), vpStatus_InvalidId);
  EXPECT_VP_OK(vpColliderGetPose(newCollider, &pose));
  ASSERT_VP_OK(vpWorldDestroy(second));
}

TEST(CApiIds, ColliderFromAnotherWorldIsNotFoundByName) {
  ScopedWorld a, b;
  ASSERT_VP_OK(vpWorldLoadScene(a.id, VP_TEST_DATA_DIR "/scenes/stack.json"));
  vpColliderId found;
  ASSERT_VP_OK(vpWorldFindCollider(a.id, "ramp", &found));
  EXPECT_EQ(found.world.index1, a.id.index1);
  EXPECT_EQ(vpWorldFindCollider(b.id, "ramp", &found), vpStatus_InvalidArgument);
}

// A C host can reinterpret one id struct as another (they share a layout): the id's kind is in
// its generation, so the wrong kind is InvalidId and touches nothing.
TEST(CApiIds, IdOfOneKindUsedAsAnotherIsInvalid) {
  ScopedWorld w;
  ASSERT_VP_OK(vpWorldLoadScene(w.id, VP_TEST_DATA_DIR "/scenes/jelly_bridge.json"));
  ASSERT_VP_OK(vpWorldLoadScene(w.id, VP_TEST_DATA_DIR "/scenes/fluid_pair.json"));
  vpColliderId post;
  vpDeformableId bridge;
  vpFluidId tank;
  ASSERT_VP_OK(vpWorldFindCollider(w.id, "post", &post));
  ASSERT_VP_OK(vpWorldFindDeformable(w.id, "bridge", &bridge));
  ASSERT_VP_OK(vpWorldFindFluid(w.id, "tank", &tank));
  ASSERT_EQ(post.index1, 1u);  // all three in slot 1: only the kind tells them apart
  ASSERT_EQ(bridge.index1, 1u);
  ASSERT_EQ(tank.index1, 1u);

  vpFluidId postAsFluid;
  vpDeformableId tankAsDeformable;
  vpColliderId bridgeAsCollider;
  std::memcpy(&postAsFluid, &post, sizeof post);
  std::memcpy(&tankAsDeformable, &tank, sizeof tank);
  std::memcpy(&bridgeAsCollider, &bridge, sizeof bridge);
  EXPECT_EQ(vpFluidDestroy(postAsFluid), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("is a collider id")) << vpGetLastError();
  EXPECT_EQ(vpDeformableDestroy(tankAsDeformable), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("is a fluid id")) << vpGetLastError();
  EXPECT_EQ(vpColliderDestroy(bridgeAsCollider), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("is a deformable id")) << vpGetLastError();
  const int32_t nodes[1] = {0};
  EXPECT_EQ(vpDeformableAttach(bridge, nodes, 1, bridgeAsCollider), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("is a deformable id")) << vpGetLastError();
  EXPECT_VP_OK(vpColliderIsValid(post));
  EXPECT_VP_OK(vpDeformableIsValid(bridge));
  EXPECT_VP_OK(vpFluidIsValid(tank));
}

// vpWorldId has 16-bit generations: a slot that has issued all of them is retired, so a
// stale world id never comes back, however many worlds come and go.
TEST(CApiIds, AWorldIdIsNeverIssuedTwice) {
  vpWorldDef def = vpDefaultWorldDef();
  vpWorldId first;
  ASSERT_VP_OK(vpWorldCreate(&def, &first));
  ASSERT_VP_OK(vpWorldDestroy(first));
  std::set<std::pair<uint16_t, uint16_t>> issued{{first.index1, first.generation}};
  for (int i = 0; i < 0x10000; ++i) {
    vpWorldId w;
    ASSERT_VP_OK(vpWorldCreate(&def, &w));
    ASSERT_TRUE(issued.insert({w.index1, w.generation}).second)
        << "world id (" << w.index1 << ", " << w.generation << ") issued again after " << i << " worlds";
    ASSERT_VP_OK(vpWorldDestroy(w));
  }
  EXPECT_EQ(vpWorldStep(first, 0.01f), vpStatus_InvalidId);
}

}  // namespace
