// A host allocator that returns NULL: every call that allocates either succeeds or returns
// OutOfMemory, and the world is left usable (or not created at all). The allocator fails at the
// k-th allocation, for every k up to the number a small scene makes from creation to its third
// step.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "capi_test_support.h"

namespace {

struct FailingAllocator {
  std::atomic<long> calls{0}, live{0};
  long failAt = 0;  // the 1-based allocation that returns NULL; 0: none
  static void* alloc(size_t size, size_t alignment, void* self) {
    auto* a = static_cast<FailingAllocator*>(self);
    if (++a->calls == a->failAt) return nullptr;
    const size_t rounded = (size + alignment - 1) / alignment * alignment;
    void* p = std::aligned_alloc(alignment, rounded ? rounded : alignment);
    if (p) ++a->live;
    return p;
  }
  static void release(void* p, void* self) {
    --static_cast<FailingAllocator*>(self)->live;
    std::free(p);
  }
};

bool okOrOutOfMemory(vpStatus s) { return s == vpStatus_Ok || s == vpStatus_OutOfMemory; }

// Creation, the scene, three steps; returns false (with a test failure) on anything but Ok or
// OutOfMemory, or a world that is unusable after an OutOfMemory.
bool runScenario(long failAt, FailingAllocator& a) {
  a.calls = 0;
  a.failAt = failAt;
  vpWorldDef def = unbudgetedWorldDef();
  vpWorldId w;
  vpStatus s = vpWorldCreate(&def, &w);
  EXPECT_TRUE(okOrOutOfMemory(s)) << "k = " << failAt << ": vpWorldCreate: " << vpGetLastError();
  if (s != vpStatus_Ok) return okOrOutOfMemory(s);
  s = vpWorldLoadScene(w, VP_TEST_DATA_DIR "/scenes/tiny_world.json");
  EXPECT_TRUE(okOrOutOfMemory(s)) << "k = " << failAt << ": vpWorldLoadScene: " << vpGetLastError();
  if (s == vpStatus_OutOfMemory) {  // all or nothing
    int32_t colliders = -1, deformables = -1, fluids = -1;
    vpWorldGetColliderCount(w, &colliders);
    vpWorldGetDeformableCount(w, &deformables);
    vpWorldGetFluidCount(w, &fluids);
    EXPECT_EQ(colliders + deformables + fluids, 0) << "k = " << failAt << ": the failed scene left actors behind";
  }
  for (int i = 0; i < 3; ++i) {
    s = vpWorldStep(w, 1.0f / 60.0f);
    EXPECT_TRUE(okOrOutOfMemory(s)) << "k = " << failAt << ": vpWorldStep: " << vpGetLastError();
  }
  // Whatever failed, once the allocator gives memory again the world steps and goes away cleanly.
  a.failAt = 0;
  EXPECT_EQ(vpWorldStep(w, 1.0f / 60.0f), vpStatus_Ok) << "k = " << failAt << ": " << vpGetLastError();
  EXPECT_EQ(vpWorldDestroy(w), vpStatus_Ok) << "k = " << failAt << ": " << vpGetLastError();
  return !::testing::Test::HasFailure();
}

TEST(CApiAllocationFailure, EveryAllocationOfASmallSceneMayFail) {
  static FailingAllocator allocator;  // outlives Bullet's frees in any order
  ASSERT_VP_OK(vpSetAllocator(&FailingAllocator::alloc, &FailingAllocator::release, &allocator));
  ASSERT_TRUE(runScenario(0, allocator));
  const long total = allocator.calls.load();
  ASSERT_GT(total, 50);
  ASSERT_EQ(allocator.live.load(), 0);
  for (long k = 1; k <= total; ++k) {
    if (!runScenario(k, allocator)) break;
    ASSERT_EQ(allocator.live.load(), 0) << "k = " << k << ": host allocations leaked";
  }
  std::printf("%ld allocations, each failed once\n", total);
  ASSERT_VP_OK(vpSetAllocator(nullptr, nullptr, nullptr));
}

}  // namespace
