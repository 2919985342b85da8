// DeformableBody's corotation and assembly (two parallel passes) against the same kernel
// bodies run as plain loops (element_assembly_reference.h): the same bits in every rotation,
// stiffness block and force, for every degree. The device assembly's test
// (tests/gpu/device_element_assembly_test.cpp) compares the device with that reference.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "deform/deformable_body.h"
#include "deform_test_util.h"
#include "element_assembly_reference.h"
#include "geometry/box_tet_mesh.h"

namespace vp {
namespace {

template <class A, class B>
bool sameBits(const A& a, const B& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

class DeformAssemblyKernels : public ::testing::TestWithParam<int> {};

// A bar clamped at x = 0 after 20 steps of sag; the assembly then runs from the rotations the
// steps left (warm start), at stiffness scale 1 (DeformableBody::elasticForces).
TEST_P(DeformAssemblyKernels, TheBodysAssemblyIsThePlainLoopsBitForBit) {
  DeformableDesc desc;
  desc.degree = GetParam();
  desc.mesh = makeBoxTetMesh({6, 2, 2}, Vec3(3, 1, 1), Vec3::Zero());
  desc.material.youngsModulus = 1e5;
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(desc, &body), Status::Ok) << lastError();
  deform_test::pinNodesAtX(*body, 0.0);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.tasks = tasks.get();
  in.gravity = Vec3(0, -9.81, 0);
  for (int i = 0; i < 20; ++i) {
    ActorStats stats;
    body->step(in, &stats);
  }
  const std::vector<double> warmStart(body->elementRotations().begin(), body->elementRotations().end());
  const testref::ElementAssembly reference =
      testref::elementAssembly(body->elementAssemblyView(), body->positions().data(), warmStart, 1.0);
  Array<double> force;
  body->elasticForces(*tasks, &force);
  EXPECT_TRUE(sameBits(body->elementRotations(), reference.quat));
  EXPECT_TRUE(sameBits(body->stepMatrix().values, reference.values));
  EXPECT_TRUE(sameBits(force, reference.force));
  double largest = 0.0;
  for (double f : reference.force) largest = std::max(largest, std::abs(f));
  EXPECT_GT(largest, 0.0);  // the bar is loaded: not a comparison of zeros
}

INSTANTIATE_TEST_SUITE_P(Degrees, DeformAssemblyKernels, ::testing::Values(1, 2, 3),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return std::string(param.param == 1 ? "linear" : param.param == 2 ? "quadratic" : "cubic");
                         });

}  // namespace
}  // namespace vp
