// Calls on one world that overlap (a host bug the threading contract forbids) are refused with
// Busy and change nothing; they never run side by side or free a world under a call. These
// tests also run under ThreadSanitizer (the tsan preset, in CI).
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

#include "capi_test_support.h"

namespace {

bool okOrBusy(vpStatus s) { return s == vpStatus_Ok || s == vpStatus_Busy; }

// Holds threads until all have started, so their calls overlap from the first one.
struct StartGate {
  std::atomic<int> waiting;
  explicit StartGate(int threads) : waiting(threads) {}
  void arriveAndWait() {
    waiting--;
    while (waiting.load() > 0) std::this_thread::yield();
  }
};

// A world whose step touches Bullet: a ground plane and a few falling balls.
void addBalls(vpWorldId w, int count) {
  vpColliderDef ground = vpDefaultColliderDef();
  ground.shape.type = vpShapeType_Plane;
  vpColliderId id;
  ASSERT_VP_OK(vpColliderCreate(w, &ground, &id));
  for (int i = 0; i < count; ++i) {
    vpColliderDef ball = dynamicBall(1.0f + 1.1f * float(i));
    ASSERT_VP_OK(vpColliderCreate(w, &ball, &id));
  }
}

// What the clock hook does while the world is inside vpWorldStep: every call on that world
// from another thread must be refused, naming the call that holds it.
struct ProbeFromInsideStep {
  vpWorldId world{};
  vpColliderId collider{};
  bool probed = false;
  std::vector<vpStatus> statuses;
  std::vector<std::string> messages;
  double seconds = 0.0;

  static double now(void* self) {
    auto* p = static_cast<ProbeFromInsideStep*>(self);
    if (!p->probed && p->world.index1 != 0) {
      p->probed = true;
      std::thread other([p] {
        vpStepStats stats = vpDefaultStepStats();
        vpTransform pose;
        vpBodyProperties properties{};
        properties.structSize = sizeof properties;
        int32_t sleeping = 0, hitCount = 0;
        const vpRay ray{vpVec3{0, 5, 0}, vpVec3{0, -1, 0}, 10.0f};
        vpQueryHit hit{};
        size_t stateSize = 0;
        const uint8_t state[64] = {};
        const vpStatus results[] = {vpWorldRaycast(p->world, &ray, nullptr, &hit, &hitCount),
                                    vpWorldOverlapSphere(p->world, vpVec3{0, 0, 0}, 1.0f, nullptr, &hit, 1, &hitCount),
                                    vpWorldGetContactEvents(p->world, nullptr, 0, &hitCount),
                                    vpColliderSetCollisionFilter(p->collider, vpCollisionFilter{2, 2}),
                                    vpWorldSaveState(p->world, nullptr, 0, &stateSize),
                                    vpWorldRestoreState(p->world, state, sizeof state),
                                    vpWorldStep(p->world, 0.01f),
                                    vpWorldGetStepStats(p->world, &stats),
                                    vpColliderGetPose(p->collider, &pose),
                                    vpColliderApplyForce(p->collider, vpVec3{1, 0, 0}, nullptr),
                                    vpColliderApplyImpulse(p->collider, vpVec3{1, 0, 0}, nullptr),
                                    vpColliderGetProperties(p->collider, &properties),
                                    vpColliderIsSleeping(p->collider, &sleeping),
                                    vpColliderSetSleeping(p->collider, 1),
                                    vpWorldDestroy(p->world)};
        for (vpStatus s : results) {
          p->statuses.push_back(s);
          p->messages.emplace_back(vpGetLastError());
        }
      });
      other.join();
    }
    p->seconds += 0.001;
    return p->seconds;
  }
};

TEST(WorldCallOverlap, CallsDuringAStepAreRefusedNamingTheStep) {
  ProbeFromInsideStep probe;
  vpWorldDef def = unbudgetedWorldDef();
  def.clock = &ProbeFromInsideStep::now;
  def.clockContext = &probe;
  ScopedWorld w(def);
  vpColliderDef ball = dynamicBall(2.0f);
  ASSERT_VP_OK(vpColliderCreate(w.id, &ball, &probe.collider));
  probe.world = w.id;
  ASSERT_VP_OK(vpWorldStep(w.id, 0.01f));
  ASSERT_TRUE(probe.probed);
  ASSERT_EQ(probe.statuses.size(), 15u);
  for (size_t i = 0; i < probe.statuses.size(); ++i) {
    EXPECT_EQ(probe.statuses[i], vpStatus_Busy) << "call " << i;
    EXPECT_NE(probe.messages[i].find("in use by vpWorldStep"), std::string::npos) << probe.messages[i];
  }
  // The refused destroy changed nothing; the world is usable and destroyable afterwards.
  vpStepStats stats = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &stats));
  EXPECT_EQ(stats.stepIndex, 1);
  ASSERT_VP_OK(vpWorldStep(w.id, 0.01f));
  ASSERT_VP_OK(vpWorldDestroy(w.id));
}

// Several threads step one world at once: each call either steps it alone or gets Busy, so the
// world's step count equals the number of calls that returned Ok.
TEST(WorldCallOverlap, ThreadsSteppingOneWorldStepItOneAtATime) {
  ScopedWorld w;
  addBalls(w.id, 8);
  const int kThreads = 4, kCalls = 300;
  std::atomic<int> stepped{0}, refused{0}, wrong{0};
  StartGate gate(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&] {
      gate.arriveAndWait();
      for (int i = 0; i < kCalls; ++i) {
        const vpStatus s = vpWorldStep(w.id, 1.0f / 240.0f);
        if (s == vpStatus_Ok) stepped++;
        else if (s == vpStatus_Busy) refused++;
        else wrong++;
      }
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(wrong.load(), 0);
  vpStepStats stats = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &stats));
  EXPECT_EQ(stats.stepIndex, stepped.load()) << refused.load() << " calls were refused";
  std::printf("%d steps, %d refused\n", stepped.load(), refused.load());
}

// One thread destroys a world while others step and query it: the destroy waits for no call
// and frees nothing a call is using; afterwards every call on the id is InvalidId.
TEST(WorldCallOverlap, DestroyRacingStepsNeverFreesAWorldUnderACall) {
  const int kRounds = 40, kCallers = 3;
  for (int round = 0; round < kRounds; ++round) {
    vpWorldDef def = unbudgetedWorldDef();
    vpWorldId w;
    ASSERT_VP_OK(vpWorldCreate(&def, &w));
    addBalls(w, 4);
    std::atomic<bool> destroyed{false};
    std::atomic<int> wrong{0};
    std::vector<std::thread> callers;
    for (int c = 0; c < kCallers; ++c)
      callers.emplace_back([&, c] {
        vpStepStats stats = vpDefaultStepStats();
        while (!destroyed.load()) {
          const vpStatus s = c == 0 ? vpWorldStep(w, 1.0f / 240.0f) : vpWorldGetStepStats(w, &stats);
          if (!okOrBusy(s) && s != vpStatus_InvalidId) wrong++;
          if (s == vpStatus_InvalidId && !destroyed.load()) {
            // Only the destroy below makes the id stale; it sets `destroyed` right after.
            while (!destroyed.load()) std::this_thread::yield();
          }
        }
        if (vpWorldStep(w, 1.0f / 240.0f) != vpStatus_InvalidId) wrong++;
      });
    vpStatus s;
    int busy = 0;
    while ((s = vpWorldDestroy(w)) == vpStatus_Busy) ++busy;
    EXPECT_EQ(s, vpStatus_Ok) << vpGetLastError();
    destroyed = true;
    for (auto& t : callers) t.join();
    EXPECT_EQ(wrong.load(), 0) << "round " << round;
  }
}

// Threads create, step, query and destroy worlds drawn from a small shared set of slots, so
// calls on the same world and on different worlds interleave in every way; every call returns
// Ok, Busy or InvalidId, and every world created is destroyed exactly once.
TEST(WorldCallOverlap, HammerCreateStepQueryDestroy) {
  constexpr int kSlots = 3, kThreads = 4, kOps = 400;
  std::atomic<uint32_t> slots[kSlots];
  for (auto& s : slots) s = 0;
  auto pack = [](vpWorldId id) { return uint32_t(id.index1) << 16 | id.generation; };
  auto unpack = [](uint32_t v) { return vpWorldId{uint16_t(v >> 16), uint16_t(v & 0xFFFF)}; };
  std::atomic<int> created{0}, destroyed{0}, wrong{0};
  StartGate gate(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      gate.arriveAndWait();
      std::mt19937 rng(1234u + unsigned(t));
      for (int op = 0; op < kOps; ++op) {
        std::atomic<uint32_t>& slot = slots[rng() % kSlots];
        const uint32_t packed = slot.load();
        const vpWorldId w = unpack(packed);
        vpStatus s = vpStatus_Ok;
        switch (rng() % 5) {
          case 0:
            if (packed == 0) {
              vpWorldDef def = unbudgetedWorldDef();
              vpWorldId fresh;
              if (vpWorldCreate(&def, &fresh) != vpStatus_Ok) { wrong++; break; }
              created++;
              uint32_t empty = 0;
              if (!slot.compare_exchange_strong(empty, pack(fresh))) {
                if (vpWorldDestroy(fresh) != vpStatus_Ok) wrong++;
                destroyed++;
              }
            }
            break;
          case 1: {
            vpColliderDef ball = dynamicBall(1.0f);
            vpColliderId id;
            s = vpColliderCreate(w, &ball, &id);
            break;
          }
          case 2: s = vpWorldStep(w, 1.0f / 240.0f); break;
          case 3: {
            vpStepStats stats = vpDefaultStepStats();
            s = vpWorldGetStepStats(w, &stats);
            break;
          }
          case 4:
            s = vpWorldDestroy(w);
            if (s == vpStatus_Ok) {
              destroyed++;
              uint32_t expected = packed;
              slot.compare_exchange_strong(expected, 0u);
            }
            break;
        }
        if (!okOrBusy(s) && s != vpStatus_InvalidId) wrong++;
      }
    });
  for (auto& t : threads) t.join();
  for (auto& slot : slots)
    if (const uint32_t packed = slot.load()) {
      ASSERT_VP_OK(vpWorldDestroy(unpack(packed)));
      destroyed++;
    }
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_EQ(created.load(), destroyed.load());
}

}  // namespace
