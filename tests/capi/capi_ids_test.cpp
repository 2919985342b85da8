// Ids: null, stale, destroyed, and from a world whose slot was reused.
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

}  // namespace
