// The host allocator carries the simulation's memory: after the default scene is loaded and
// stepped, nearly all of the heap the library holds came through vpSetAllocator. What may stay
// on the C++ heap is small bookkeeping (names, scene text, per-actor records), bounded by
// kMaxOutsideShare of what the host allocator holds.
#include <malloc.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

#include "capi_test_support.h"

namespace {

// The C++ heap may hold this share of what the host allocator holds: strings, maps of names,
// the scene's parsed JSON while it loads, Bullet's small per-body records.
constexpr double kMaxOutsideShare = 0.02;

struct LiveBytesAllocator {
  std::atomic<long long> live{0};
  static void* alloc(size_t size, size_t alignment, void* self) {
    const size_t rounded = (size + alignment - 1) / alignment * alignment;
    void* p = std::aligned_alloc(alignment, rounded ? rounded : alignment);
    if (p) static_cast<LiveBytesAllocator*>(self)->live += static_cast<long long>(malloc_usable_size(p));
    return p;
  }
  static void release(void* p, void* self) {
    if (p) static_cast<LiveBytesAllocator*>(self)->live -= static_cast<long long>(malloc_usable_size(p));
    std::free(p);
  }
};

// Bytes the process holds on glibc's heap (all arenas and mmapped chunks).
long long heapInUse() {
  const struct mallinfo2 info = mallinfo2();
  return static_cast<long long>(info.uordblks + info.hblkhd);
}

bool heapIsGlibcs() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return false;  // the sanitizers replace malloc; mallinfo2 then says nothing
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
  return false;
#else
  return true;
#endif
#else
  return true;
#endif
}

TEST(CApiHostMemory, TheDefaultScenesMemoryGoesThroughTheHostAllocator) {
  if (!heapIsGlibcs()) GTEST_SKIP() << "needs glibc's malloc statistics (not under a sanitizer)";
  static LiveBytesAllocator allocator;  // outlives Bullet's frees in any order
  ASSERT_VP_OK(vpSetAllocator(&LiveBytesAllocator::alloc, &LiveBytesAllocator::release, &allocator));
  malloc_trim(0);
  const long long heapBefore = heapInUse();
  const long long hostBefore = allocator.live.load();
  {
    ScopedWorld w;
    ASSERT_VP_OK(vpWorldLoadScene(w.id, VP_TEST_DATA_DIR "/../../sample_host/scenes/default.json"));
    // The scene sets a frame budget; without one, what has been allocated after five frames
    // does not depend on how fast (or busy) the machine is.
    ASSERT_VP_OK(vpWorldSetFrameBudget(w.id, 0.0f));
    for (int frame = 0; frame < 5; ++frame) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
    const long long host = allocator.live.load() - hostBefore;
    const long long outside = heapInUse() - heapBefore - host;
    std::printf("host allocator %.2f MB, C++ heap outside it %.2f MB\n", host / 1e6, outside / 1e6);
    EXPECT_GT(host, 1000000);
    EXPECT_LE(static_cast<double>(outside), kMaxOutsideShare * static_cast<double>(host))
        << "the C++ heap holds " << outside << " bytes beside the host allocator's " << host;
  }
  EXPECT_EQ(allocator.live.load(), hostBefore);
  ASSERT_VP_OK(vpSetAllocator(nullptr, nullptr, nullptr));
}

}  // namespace
