// Helpers for the C ABI tests.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

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

// A 2x1x1 box of 2 cubes (12 tets) as plain arrays.
struct BoxArrays {
  std::vector<float> vertices;
  std::vector<int32_t> tets;
  BoxArrays() {
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) vertices.insert(vertices.end(), {float(i), float(j), float(k)});
    auto v = [](int i, int j, int k) { return i + 3 * (j + 2 * k); };
    const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int cube = 0; cube < 2; ++cube)
      for (const auto& o : orders) {
        int c[3] = {cube, 0, 0};
        int32_t t[4];
        t[0] = v(c[0], c[1], c[2]);
        for (int s = 0; s < 3; ++s) c[o[s]]++, t[s + 1] = v(c[0], c[1], c[2]);
        tets.insert(tets.end(), t, t + 4);  // orientation repaired by the library if needed
      }
  }
  vpDeformableDef def() const {
    vpDeformableDef d = vpDefaultDeformableDef();
    d.vertices = vertices.data();
    d.vertexCount = static_cast<int32_t>(vertices.size() / 3);
    d.tets = tets.data();
    d.tetCount = static_cast<int32_t>(tets.size() / 4);
    return d;
  }
};
