// Contact events: a box dropped on a floor begins touching it once, rests without events,
// ends touching when lifted away; a floor it does not meet gives none.
#include <vector>

#include "capi_test_support.h"

namespace {

constexpr float kDt = 1.0f / 60.0f;

std::vector<vpContactEvent> eventsOf(vpWorldId w) {
  int32_t count = -1;
  EXPECT_VP_OK(vpWorldGetContactEvents(w, nullptr, 0, &count));
  std::vector<vpContactEvent> events(static_cast<size_t>(count));
  int32_t again = -1;
  EXPECT_VP_OK(vpWorldGetContactEvents(w, events.data(), count, &again));
  EXPECT_EQ(again, count);
  return events;
}

struct BoxOnFloor {
  ScopedWorld world;
  BoxArrays box;
  vpColliderId floor{};
  vpDeformableId jelly{};
  explicit BoxOnFloor(vpCollisionFilter floorFilter = vpDefaultColliderDef().filter) {
    vpColliderDef plane = vpDefaultColliderDef();
    plane.shape.type = vpShapeType_Plane;
    plane.filter = floorFilter;
    EXPECT_VP_OK(vpColliderCreate(world.id, &plane, &floor));
    vpColliderDef aside = vpDefaultColliderDef();  // a sphere far away: never touched
    aside.pose.position = vpVec3{20, 1, 0};
    vpColliderId other{};
    EXPECT_VP_OK(vpColliderCreate(world.id, &aside, &other));
    vpDeformableDef def = box.def();
    def.pose.position = vpVec3{0, 0.3f, 0};
    EXPECT_VP_OK(vpDeformableCreate(world.id, &def, &jelly));
  }
};

TEST(CApiContactEvents, ABoxBeginsTouchingTheFloorOnceAndEndsWhenLifted) {
  BoxOnFloor scene;
  int begins = 0, frameOfBegin = -1;
  vpContactEvent begin{};
  for (int frame = 0; frame < 90; ++frame) {
    ASSERT_VP_OK(vpWorldStep(scene.world.id, kDt));
    for (const vpContactEvent& e : eventsOf(scene.world.id)) {
      ASSERT_EQ(e.type, vpContactEventType_Begin) << "frame " << frame;  // resting makes no End
      begin = e;
      frameOfBegin = frame;
      ++begins;
    }
  }
  ASSERT_EQ(begins, 1);
  EXPECT_LT(frameOfBegin, 30);  // 0.3 m of free fall takes 0.25 s
  EXPECT_EQ(begin.deformable.index1, scene.jelly.index1);
  EXPECT_EQ(begin.collider.index1, scene.floor.index1);
  EXPECT_GE(begin.nodeCount, 1);
  EXPECT_NEAR(begin.point.y, 0.0f, 0.05f);
  EXPECT_NEAR(begin.normal.y, 1.0f, 1e-3f);

  // Lifted 2 m and stepped: the pair ends, once.
  std::vector<float> x(3 * 12);
  ASSERT_VP_OK(vpDeformableGetPositions(scene.jelly, x.data(), 12));
  for (int i = 0; i < 12; ++i) x[3 * i + 1] += 2.0f;
  ASSERT_VP_OK(vpDeformableSetPositions(scene.jelly, x.data(), 12, 1));
  ASSERT_VP_OK(vpWorldStep(scene.world.id, kDt));
  const std::vector<vpContactEvent> lifted = eventsOf(scene.world.id);
  ASSERT_EQ(lifted.size(), 1u);
  EXPECT_EQ(lifted[0].type, vpContactEventType_End);
  EXPECT_EQ(lifted[0].collider.index1, scene.floor.index1);
  EXPECT_EQ(lifted[0].nodeCount, 0);
  ASSERT_VP_OK(vpWorldStep(scene.world.id, kDt));
  EXPECT_TRUE(eventsOf(scene.world.id).empty());
}

TEST(CApiContactEvents, AFloorTheBoxDoesNotMeetGivesNoEvents) {
  BoxOnFloor scene(vpCollisionFilter{2, 0xFFFFFFFFu & ~1u});
  for (int frame = 0; frame < 60; ++frame) {
    ASSERT_VP_OK(vpWorldStep(scene.world.id, kDt));
    EXPECT_TRUE(eventsOf(scene.world.id).empty()) << "frame " << frame;
  }
}

TEST(CApiContactEvents, BadArgumentsAreNamedAndAShortBufferGetsTheCount) {
  BoxOnFloor scene;
  int32_t count = 0;
  EXPECT_EQ(vpWorldGetContactEvents(scene.world.id, nullptr, 0, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("outCount is NULL")) << vpGetLastError();
  EXPECT_EQ(vpWorldGetContactEvents(scene.world.id, nullptr, -1, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("capacity = -1")) << vpGetLastError();
  EXPECT_EQ(vpWorldGetContactEvents(scene.world.id, nullptr, 2, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("outEvents is NULL with capacity = 2")) << vpGetLastError();
  for (int frame = 0; frame < 40 && count == 0; ++frame) {
    ASSERT_VP_OK(vpWorldStep(scene.world.id, kDt));
    ASSERT_VP_OK(vpWorldGetContactEvents(scene.world.id, nullptr, 0, &count));
  }
  EXPECT_EQ(count, 1);
}

}  // namespace
