// vpWorldSaveState / vpWorldRestoreState through the C ABI: round trips, the size protocol,
// and every way a buffer can be wrong (truncated, each byte flipped, another format, another
// world, hostile values under a valid checksum) refused with a named reason and the world
// unchanged. The bitwise continuation of whole scenes is tested in unit/world_state_test.cpp.
#include <cstdint>
#include <vector>

#include "capi_test_support.h"

namespace {

// A small world with one of each: a static ground, a ball resting on it, a jelly, smoke.
struct SmallWorld : ScopedWorld {
  vpColliderId ground{}, ball{};
  vpDeformableId jelly{};
  vpFluidId smoke{};
  BoxArrays box;
  explicit SmallWorld(bool withBall = true) {
    vpColliderDef plane = vpDefaultColliderDef();
    plane.bodyType = vpBodyType_Static;
    plane.shape.type = vpShapeType_Plane;
    EXPECT_VP_OK(vpColliderCreate(id, &plane, &ground));
    if (withBall) {
      const vpColliderDef b = dynamicBall(0.5f, 0.5f);
      EXPECT_VP_OK(vpColliderCreate(id, &b, &ball));
    }
    vpDeformableDef d = box.def();
    d.pose.position = vpVec3{2.0f, 0.5f, 0.0f};
    EXPECT_VP_OK(vpDeformableCreate(id, &d, &jelly));
    vpFluidDef f = vpDefaultFluidDef();
    f.resolution[0] = f.resolution[1] = f.resolution[2] = 4;
    f.cellSize = 0.25f;
    f.origin = vpVec3{-0.5f, 0.0f, -0.5f};
    EXPECT_VP_OK(vpFluidCreate(id, &f, &smoke));
    for (int i = 0; i < 10; ++i) EXPECT_VP_OK(vpWorldStep(id, 1.0f / 60.0f));
  }
  std::vector<uint8_t> save() const {
    size_t size = 0;
    EXPECT_VP_OK(vpWorldSaveState(id, nullptr, 0, &size));
    std::vector<uint8_t> buffer(size);
    size_t written = 0;
    EXPECT_VP_OK(vpWorldSaveState(id, buffer.data(), buffer.size(), &written));
    EXPECT_EQ(written, size);
    return buffer;
  }
};

// The header's layout (snapshot/state_stream.cpp): 40 bytes, the checksum last.
constexpr size_t kHeaderSize = 40, kVersionOffset = 8, kChecksumOffset = 32;

uint64_t fnv1a(const uint8_t* data, size_t size) {
  uint64_t h = 14695981039346656037ull;
  for (size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ull;
  return h;
}

void resign(std::vector<uint8_t>& buffer) {
  const uint64_t sum = fnv1a(buffer.data() + kHeaderSize, buffer.size() - kHeaderSize);
  std::memcpy(buffer.data() + kChecksumOffset, &sum, sizeof sum);
}

TEST(CApiWorldState, RoundTripInTheSameWorld) {
  SmallWorld w;
  const std::vector<uint8_t> saved = w.save();
  vpTransform before{};
  ASSERT_VP_OK(vpColliderGetPose(w.ball, &before));
  vpVec3 push{0, 0, 5};
  ASSERT_VP_OK(vpColliderApplyImpulse(w.ball, push, nullptr));
  for (int i = 0; i < 20; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  vpTransform moved{};
  ASSERT_VP_OK(vpColliderGetPose(w.ball, &moved));
  EXPECT_GT(moved.position.z, before.position.z + 0.1f);
  ASSERT_VP_OK(vpWorldRestoreState(w.id, saved.data(), saved.size()));
  vpTransform back{};
  ASSERT_VP_OK(vpColliderGetPose(w.ball, &back));
  EXPECT_EQ(std::memcmp(&back, &before, sizeof back), 0);
  EXPECT_EQ(w.save(), saved);  // nothing else moved either
}

TEST(CApiWorldState, SizeProtocolAndBadArguments) {
  SmallWorld w;
  size_t size = 0;
  ASSERT_VP_OK(vpWorldSaveState(w.id, nullptr, 0, &size));
  EXPECT_GT(size, kHeaderSize);
  std::vector<uint8_t> small(size - 1);
  size_t reported = 0;
  EXPECT_EQ(vpWorldSaveState(w.id, small.data(), small.size(), &reported), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("capacity")) << vpGetLastError();
  EXPECT_EQ(reported, size);
  EXPECT_EQ(vpWorldSaveState(w.id, nullptr, 16, &reported), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("buffer is NULL")) << vpGetLastError();
  EXPECT_EQ(vpWorldSaveState(w.id, small.data(), small.size(), nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("outSize")) << vpGetLastError();
  EXPECT_EQ(vpWorldRestoreState(w.id, nullptr, 8), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("buffer")) << vpGetLastError();
  const vpWorldId stale{w.id.index1, static_cast<uint16_t>(w.id.generation + 1)};
  EXPECT_EQ(vpWorldSaveState(stale, nullptr, 0, &reported), vpStatus_InvalidId);
  EXPECT_EQ(vpWorldRestoreState(stale, small.data(), small.size()), vpStatus_InvalidId);
}

// Every corruption is refused and changes nothing (the state saved after the attempt is the
// one saved before it).
TEST(CApiWorldState, TruncatedAndCorruptedBuffersAreRefused) {
  SmallWorld w;
  const std::vector<uint8_t> saved = w.save();
  for (size_t n = 0; n < saved.size(); ++n) {
    ASSERT_EQ(vpWorldRestoreState(w.id, saved.data(), n), vpStatus_ParseError) << n << " bytes";
  }
  EXPECT_TRUE(lastErrorContains("truncated")) << vpGetLastError();
  std::vector<uint8_t> flipped = saved;
  for (size_t i = 0; i < flipped.size(); ++i) {
    flipped[i] ^= 0x5A;
    const vpStatus s = vpWorldRestoreState(w.id, flipped.data(), flipped.size());
    ASSERT_NE(s, vpStatus_Ok) << "byte " << i;
    flipped[i] ^= 0x5A;
  }
  EXPECT_EQ(w.save(), saved);
  std::vector<uint8_t> padded = saved;
  padded.push_back(0);
  EXPECT_EQ(vpWorldRestoreState(w.id, padded.data(), padded.size()), vpStatus_ParseError);
  std::vector<uint8_t> corrupted = saved;
  corrupted[corrupted.size() / 2] ^= 1;
  EXPECT_EQ(vpWorldRestoreState(w.id, corrupted.data(), corrupted.size()), vpStatus_ParseError);
  EXPECT_TRUE(lastErrorContains("checksum")) << vpGetLastError();
  const char notAState[64] = "{\"version\": 1, \"world\": {}}";
  EXPECT_EQ(vpWorldRestoreState(w.id, notAState, sizeof notAState), vpStatus_ParseError);
  EXPECT_TRUE(lastErrorContains("not a VolPhys saved state")) << vpGetLastError();
}

TEST(CApiWorldState, AnotherFormatVersionIsRefused) {
  SmallWorld w;
  std::vector<uint8_t> saved = w.save();
  saved[kVersionOffset] += 1;
  EXPECT_EQ(vpWorldRestoreState(w.id, saved.data(), saved.size()), vpStatus_VersionMismatch);
  EXPECT_TRUE(lastErrorContains("format")) << vpGetLastError();
}

TEST(CApiWorldState, AnotherWorldsStateIsRefused) {
  SmallWorld w;
  const std::vector<uint8_t> saved = w.save();
  SmallWorld noBall(false);
  const std::vector<uint8_t> own = noBall.save();
  EXPECT_EQ(vpWorldRestoreState(noBall.id, saved.data(), saved.size()), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("collider count is 2; this world's is 1")) << vpGetLastError();
  EXPECT_EQ(noBall.save(), own);

  // Same actors, another fluid grid.
  SmallWorld other;
  ASSERT_VP_OK(vpFluidDestroy(other.smoke));
  vpFluidDef f = vpDefaultFluidDef();
  f.resolution[0] = f.resolution[1] = f.resolution[2] = 5;
  vpFluidId bigger{};
  ASSERT_VP_OK(vpFluidCreate(other.id, &f, &bigger));
  EXPECT_EQ(vpWorldRestoreState(other.id, saved.data(), saved.size()), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("fluid id")) << vpGetLastError();  // a new slot generation
}

// A buffer with a valid checksum but impossible values (a hostile or buggy writer) is
// refused too: the reader checks ranges, not only the checksum.
TEST(CApiWorldState, ImpossibleValuesUnderAValidChecksumAreRefused) {
  SmallWorld w;
  const std::vector<uint8_t> saved = w.save();
  // A huge count (as a double: NaN) written at every 4-byte offset of the first kilobyte of
  // the payload, which holds the world's counts and the colliders' states.
  int refused = 0, tried = 0;
  for (size_t at = kHeaderSize; at + 8 <= saved.size() && at < kHeaderSize + 1024; at += 4) {
    std::vector<uint8_t> bad = saved;
    const uint64_t hugeCount = ~uint64_t(0) >> 1;
    std::memcpy(bad.data() + at, &hugeCount, sizeof hugeCount);
    resign(bad);
    ++tried;
    const vpStatus s = vpWorldRestoreState(w.id, bad.data(), bad.size());
    refused += s != vpStatus_Ok;
    if (s == vpStatus_Ok) {
      ASSERT_VP_OK(vpWorldRestoreState(w.id, saved.data(), saved.size()));
    }
  }
  // Two of these writes make a legal state: over the step index (any value is one), and over
  // the ground's unused padding word and the low bits of its sleep timer (still finite).
  EXPECT_EQ(refused, tried - 2);
  EXPECT_EQ(w.save(), saved);
}

}  // namespace
