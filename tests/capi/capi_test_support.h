// Helpers for the C ABI tests.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "volphys/volphys.h"

#define EXPECT_VP_OK(call) EXPECT_EQ((call), vpStatus_Ok) << vpGetLastError()
#define ASSERT_VP_OK(call) ASSERT_EQ((call), vpStatus_Ok) << vpGetLastError()

inline bool lastErrorContains(const std::string& part) {
  return std::string(vpGetLastError()).find(part) != std::string::npos;
}

// A world that is destroyed at the end of the test.
// No frame budget by default: physics assertions must not depend on how fast the (possibly
// sanitizer-instrumented, shared) machine is. Budget behaviour has tests of its own.
inline vpWorldDef unbudgetedWorldDef() {
  vpWorldDef def = vpDefaultWorldDef();
  def.frameBudgetMs = 0.0f;
  return def;
}

struct ScopedWorld {
  vpWorldId id{};
  explicit ScopedWorld(vpWorldDef def = unbudgetedWorldDef()) { EXPECT_VP_OK(vpWorldCreate(&def, &id)); }
  ~ScopedWorld() {
    if (vpWorldIsValid(id) == vpStatus_Ok) vpWorldDestroy(id);
  }
};

inline vpColliderDef dynamicBall(float y, float radius = 0.5f) {
  vpColliderDef def = vpDefaultColliderDef();
  def.bodyType = vpBodyType_Dynamic;
  def.shape.radius = radius;
  def.pose.position.y = y;
  return def;
}

// Writes an arbitrary int into a C enum field, as a C host could (a C++ cast to an
// out-of-range enum value would itself be undefined).
template <class Enum>
void setRawEnum(Enum& field, int value) {
  std::memcpy(&field, &value, sizeof value);
}
