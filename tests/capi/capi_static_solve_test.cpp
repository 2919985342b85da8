// vpDeformableSolveStatic through the C ABI: a box jelly dropped onto a ground plane from above
// settles on it at rest; bad arguments are named and change nothing.
#include <algorithm>
#include <cmath>
#include <vector>

#include "capi_test_support.h"

namespace {

struct JellyAboveGround {
  ScopedWorld w;
  BoxArrays box;
  vpDeformableId jelly{};
  JellyAboveGround() {
    vpColliderDef ground = vpDefaultColliderDef();
    ground.shape.type = vpShapeType_Plane;
    ground.shape.normal = vpVec3{0, 1, 0};
    vpColliderId g{};
    EXPECT_VP_OK(vpColliderCreate(w.id, &ground, &g));
    vpDeformableDef def = box.def();  // [0, 2] x [0, 1] x [0, 1]
    def.degree = 2;
    def.youngsModulus = 2e5f;
    def.pose.position = vpVec3{0, 0.1f, 0};
    EXPECT_VP_OK(vpDeformableCreate(w.id, &def, &jelly));
  }
  std::vector<float> read(vpStatus (*get)(vpDeformableId, float*, int32_t)) const {
    int32_t n = 0;
    EXPECT_VP_OK(vpDeformableGetNodeCount(jelly, &n));
    std::vector<float> out(3 * static_cast<size_t>(n));
    EXPECT_VP_OK(get(jelly, out.data(), n));
    return out;
  }
};

TEST(CApiStaticSolve, AJellyAboveTheGroundSettlesOnItAtRest) {
  JellyAboveGround s;
  int32_t iterations = -1;
  float residual = -1.0f;
  ASSERT_VP_OK(vpDeformableSolveStatic(s.jelly, 200, 1e-4f, &iterations, &residual));
  EXPECT_GT(iterations, 0);
  EXPECT_LE(residual, 1e-4f);
  const std::vector<float> x = s.read(vpDeformableGetPositions), v = s.read(vpDeformableGetVelocities);
  float lowest = 1e9f, highest = -1e9f;
  for (size_t i = 1; i < x.size(); i += 3) lowest = std::min(lowest, x[i]), highest = std::max(highest, x[i]);
  EXPECT_GE(lowest, -1e-5f);
  EXPECT_LT(lowest, 0.01f) << "it came down onto the ground";
  EXPECT_LT(highest, 1.0f) << "and sags under its weight";
  for (float vi : v) EXPECT_EQ(vi, 0.0f);
  // NULL outputs are allowed; from the equilibrium it converges at once.
  EXPECT_VP_OK(vpDeformableSolveStatic(s.jelly, 200, 1e-3f, nullptr, nullptr));
}

TEST(CApiStaticSolve, BadArgumentsAreNamedAndChangeNothing) {
  JellyAboveGround s;
  const std::vector<float> x0 = s.read(vpDeformableGetPositions);
  EXPECT_EQ(vpDeformableSolveStatic(s.jelly, 0, 1e-4f, nullptr, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("maxIterations = 0")) << vpGetLastError();
  EXPECT_EQ(vpDeformableSolveStatic(s.jelly, 20001, 1e-4f, nullptr, nullptr), vpStatus_InvalidArgument);
  EXPECT_EQ(vpDeformableSolveStatic(s.jelly, 10, NAN, nullptr, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("tolerance = nan")) << vpGetLastError();
  EXPECT_EQ(vpDeformableSolveStatic(s.jelly, 10, 1.0f, nullptr, nullptr), vpStatus_InvalidArgument);
  EXPECT_EQ(vpDeformableSolveStatic(vpDeformableId{}, 10, 1e-4f, nullptr, nullptr), vpStatus_InvalidId);
  int32_t iterations = 0;
  float residual = 0.0f;
  EXPECT_EQ(vpDeformableSolveStatic(s.jelly, 1, 1e-9f, &iterations, &residual), vpStatus_NotConverged);
  EXPECT_EQ(iterations, 1);
  EXPECT_GT(residual, 1e-9f);
  EXPECT_TRUE(lastErrorContains("unchanged")) << vpGetLastError();
  EXPECT_EQ(s.read(vpDeformableGetPositions), x0);
}

}  // namespace
