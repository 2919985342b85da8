// vpColliderGetName, vpDeformableGetName, vpFluidGetName: scene names copied out with their
// terminator, the length asked with a NULL buffer, short buffers and bad arguments refused.
#include <string>

#include "capi_test_support.h"

namespace {

// Both calls of the usual pattern: ask the length, then copy into a buffer of that size.
template <class Id, class GetName>
std::string nameOf(Id id, GetName getName) {
  int32_t length = -1;
  EXPECT_VP_OK(getName(id, nullptr, 0, &length));
  if (length < 1) return "<no length>";
  std::string name(static_cast<size_t>(length), '?');
  int32_t again = -1;
  EXPECT_VP_OK(getName(id, name.data(), length, &again));
  EXPECT_EQ(again, length);
  EXPECT_EQ(name.back(), '\0');
  name.pop_back();
  return name;
}

struct NamedScene : ScopedWorld {
  vpColliderId post{};
  vpDeformableId bridge{};
  vpFluidId tank{};
  NamedScene() {
    EXPECT_VP_OK(vpWorldLoadScene(id, VP_TEST_DATA_DIR "/scenes/jelly_bridge.json"));
    EXPECT_VP_OK(vpWorldLoadScene(id, VP_TEST_DATA_DIR "/scenes/fluid_pair.json"));
    EXPECT_VP_OK(vpWorldFindCollider(id, "post", &post));
    EXPECT_VP_OK(vpWorldFindDeformable(id, "bridge", &bridge));
    EXPECT_VP_OK(vpWorldFindFluid(id, "tank", &tank));
  }
};

}  // namespace

TEST(CApiActorNames, NamesFromTheSceneFile) {
  NamedScene s;
  EXPECT_EQ(nameOf(s.post, vpColliderGetName), "post");
  EXPECT_EQ(nameOf(s.bridge, vpDeformableGetName), "bridge");
  EXPECT_EQ(nameOf(s.tank, vpFluidGetName), "tank");
  // Every actor the world lists has the name it is found by.
  int32_t count = 0;
  ASSERT_VP_OK(vpWorldGetFluidCount(s.id, &count));
  std::vector<vpFluidId> fluids(static_cast<size_t>(count));
  ASSERT_VP_OK(vpWorldGetFluids(s.id, fluids.data(), count, &count));
  for (vpFluidId f : fluids) {
    vpFluidId found{};
    ASSERT_VP_OK(vpWorldFindFluid(s.id, nameOf(f, vpFluidGetName).c_str(), &found));
    EXPECT_EQ(found.index1, f.index1);
  }
}

TEST(CApiActorNames, UnnamedActorsHaveAnEmptyName) {
  ScopedWorld w;
  vpColliderDef ball = dynamicBall(1.0f);
  vpColliderId collider;
  ASSERT_VP_OK(vpColliderCreate(w.id, &ball, &collider));
  BoxArrays box;
  vpDeformableDef boxDef = box.def();
  vpDeformableId deformable;
  ASSERT_VP_OK(vpDeformableCreate(w.id, &boxDef, &deformable));
  vpFluidDef smoke = vpDefaultFluidDef();
  smoke.resolution[0] = smoke.resolution[1] = smoke.resolution[2] = 4;
  vpFluidId fluid;
  ASSERT_VP_OK(vpFluidCreate(w.id, &smoke, &fluid));

  int32_t length = -1;
  char buffer[4] = {'x', 'x', 'x', 'x'};
  ASSERT_VP_OK(vpColliderGetName(collider, buffer, 4, &length));
  EXPECT_EQ(length, 1);
  EXPECT_EQ(buffer[0], '\0');
  EXPECT_EQ(nameOf(deformable, vpDeformableGetName), "");
  EXPECT_EQ(nameOf(fluid, vpFluidGetName), "");
}

TEST(CApiActorNames, AShortBufferGetsTheLengthAndNothingElse) {
  NamedScene s;
  char buffer[8] = {'x', 'x', 'x', 'x', 'x', 'x', 'x', 'x'};
  int32_t length = -1;
  // "bridge" needs 7 bytes: 6 is one short, 7 fits exactly.
  EXPECT_EQ(vpDeformableGetName(s.bridge, buffer, 6, &length), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("capacity = 6: the name needs 7 bytes")) << vpGetLastError();
  EXPECT_EQ(length, 7);
  EXPECT_EQ(std::string(buffer, 8), "xxxxxxxx");
  // A non-NULL buffer with capacity 0 is a short buffer too, not a length query.
  EXPECT_EQ(vpFluidGetName(s.tank, buffer, 0, &length), vpStatus_InvalidArgument);
  EXPECT_EQ(length, 5);
  EXPECT_EQ(std::string(buffer, 8), "xxxxxxxx");
  ASSERT_VP_OK(vpDeformableGetName(s.bridge, buffer, 7, &length));
  EXPECT_STREQ(buffer, "bridge");
  EXPECT_EQ(buffer[7], 'x');
}

TEST(CApiActorNames, BadArgumentsAreRefusedByName) {
  NamedScene s;
  char buffer[16];
  int32_t length = -1;
  EXPECT_EQ(vpColliderGetName(s.post, buffer, 16, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("outLength is NULL")) << vpGetLastError();
  EXPECT_EQ(vpColliderGetName(s.post, nullptr, 16, &length), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("buffer is NULL with capacity = 16")) << vpGetLastError();
  EXPECT_EQ(length, -1);
  EXPECT_EQ(vpFluidGetName(s.tank, buffer, -1, &length), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("capacity = -1")) << vpGetLastError();
  EXPECT_EQ(length, -1);
}

TEST(CApiActorNames, BadIdsAreInvalidId) {
  NamedScene s;
  char buffer[16];
  int32_t length = -1;
  EXPECT_EQ(vpColliderGetName(vpColliderId{}, buffer, 16, &length), vpStatus_InvalidId);
  EXPECT_EQ(vpDeformableGetName(vpDeformableId{}, buffer, 16, &length), vpStatus_InvalidId);
  // An id of another kind (the same slot) and a destroyed fluid's id.
  vpFluidId postAsFluid;
  std::memcpy(&postAsFluid, &s.post, sizeof postAsFluid);
  EXPECT_EQ(vpFluidGetName(postAsFluid, buffer, 16, &length), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("is a collider id")) << vpGetLastError();
  ASSERT_VP_OK(vpFluidDestroy(s.tank));
  EXPECT_EQ(vpFluidGetName(s.tank, buffer, 16, &length), vpStatus_InvalidId);
  EXPECT_EQ(length, -1);
}
