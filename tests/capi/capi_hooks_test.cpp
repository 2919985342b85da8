// Host task, clock, allocator and log hooks.
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <string>

#include "capi_test_support.h"

namespace {

struct TaskLog {
  std::atomic<int> enqueued{0};
};

void* enqueueInline(vpTaskFn* task, int32_t count, int32_t, void* taskContext, void* user) {
  static_cast<TaskLog*>(user)->enqueued++;
  task(0, count, 0, taskContext);
  return nullptr;
}
void finishNothing(void*, void*) { ADD_FAILURE() << "finishTask called for an inline task"; }

TEST(CApiHooks, HostTaskSystemIsAccepted) {
  TaskLog log;
  vpWorldDef def = vpDefaultWorldDef();
  def.workerCount = 4;
  def.enqueueTask = &enqueueInline;
  def.finishTask = &finishNothing;
  def.userTaskContext = &log;
  ScopedWorld w(def);
  ASSERT_VP_OK(vpWorldLoadScene(w.id, VP_TEST_DATA_DIR "/scenes/stack.json"));
  for (int i = 0; i < 10; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  // Rigid-only worlds have no parallel loops yet; the hook must simply not break anything.
  EXPECT_GE(log.enqueued.load(), 0);
}

struct FakeClock {
  double seconds = 0.0;
  static double now(void* self) {
    auto* c = static_cast<FakeClock*>(self);
    c->seconds += 0.001;  // every query advances 1 ms
    return c->seconds;
  }
};

TEST(CApiHooks, InjectedClockDrivesStepTiming) {
  FakeClock clock;
  vpWorldDef def = vpDefaultWorldDef();
  def.clock = &FakeClock::now;
  def.clockContext = &clock;
  ScopedWorld w(def);
  ASSERT_VP_OK(vpWorldStep(w.id, 0.01f));
  vpStepStats stats = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &stats));
  EXPECT_GT(clock.seconds, 0.0);
  // Timings are whole multiples of the fake clock's 1 ms tick: deterministic.
  EXPECT_NEAR(stats.totalMs, std::round(stats.totalMs), 1e-3);
  EXPECT_GE(stats.totalMs, 1.0f);
}

struct CountingAllocator {
  std::atomic<long> allocations{0}, frees{0};
  static void* alloc(size_t size, size_t alignment, void* self) {
    static_cast<CountingAllocator*>(self)->allocations++;
    size_t rounded = (size + alignment - 1) / alignment * alignment;
    return std::aligned_alloc(alignment, rounded ? rounded : alignment);
  }
  static void release(void* p, void* self) {
    static_cast<CountingAllocator*>(self)->frees++;
    std::free(p);
  }
};

TEST(CApiHooks, AllocatorRoutesBulletAllocations) {
  static CountingAllocator counter;  // outlives Bullet's frees in any order
  ASSERT_VP_OK(vpSetAllocator(&CountingAllocator::alloc, &CountingAllocator::release, &counter));
  {
    ScopedWorld w;
    // Setting the allocator while a world exists would mix heaps.
    EXPECT_EQ(vpSetAllocator(nullptr, nullptr, nullptr), vpStatus_Busy);
    EXPECT_TRUE(lastErrorContains("world(s) exist"));
    ASSERT_VP_OK(vpWorldLoadScene(w.id, VP_TEST_DATA_DIR "/scenes/stack.json"));
    for (int i = 0; i < 5; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  }
  EXPECT_GT(counter.allocations.load(), 10);
  EXPECT_EQ(counter.allocations.load(), counter.frees.load());
  ASSERT_VP_OK(vpSetAllocator(nullptr, nullptr, nullptr));
  EXPECT_EQ(vpSetAllocator(&CountingAllocator::alloc, nullptr, nullptr), vpStatus_InvalidArgument);
}

TEST(CApiHooks, LogCallbackReceivesMessagesAtItsLevel) {
  // An out-of-range level can only be passed from C (in C++ the load itself is undefined);
  // tests/capi/c99_smoke.c checks that it is rejected.
  static std::atomic<int> calls{0};
  static std::string lastMessage;
  auto sink = [](vpLogLevel level, const char* message, void*) {
    calls++;
    if (level == vpLogLevel_Info) lastMessage = message;
  };
  ASSERT_VP_OK(vpSetLogCallback(+sink, nullptr, vpLogLevel_Info));
  { ScopedWorld w; }  // world creation is logged at Info level
  EXPECT_GE(calls.load(), 1);
  EXPECT_NE(lastMessage.find("world created"), std::string::npos) << lastMessage;
  ASSERT_VP_OK(vpSetLogCallback(+sink, nullptr, vpLogLevel_Warning));
  const int before = calls.load();
  { ScopedWorld w; }
  EXPECT_EQ(calls.load(), before);  // below the level: not delivered
  ASSERT_VP_OK(vpSetLogCallback(nullptr, nullptr, vpLogLevel_Warning));
}

}  // namespace
