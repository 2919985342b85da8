// Corotation and assembly on the device (gpu::DeviceElementAssembly) against the same kernel
// bodies run by a CPU loop (tests/unit/element_assembly_reference.h, which
// DeformAssemblyKernels.* holds to DeformableBody's own assembly). The device file is
// built with --fmad=false and the bodies use only correctly rounded operations (+, −, ×, ÷,
// sqrt), so every rotation, block and force must be the CPU's bits. ctest label gpu; skipped
// by name without a device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "beam_mesh.h"
#include "deform/deformable_body.h"
#include "deform_beam_desc.h"
#include "gpu_kernels/device_element_assembly.h"
#include "gpu_kernels/device_query.h"
#include "element_assembly_reference.h"

namespace vp::gpu_test {
namespace {

class DeviceElementAssembly : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    if (gpu::cudaDeviceCount() == 0) GTEST_SKIP() << "no CUDA device on this machine";
  }
};

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// A 1536-tet beam of the degree after 20 steps of sag, its rotations restarted from the
// identity (so every element iterates), and the same beam mirrored through z = 0 (every element
// inverted: the SVD path).
TEST_P(DeviceElementAssembly, ABentAndAnInvertedBeamGiveTheCpuBits) {
  const int degree = GetParam();
  bench::BeamCells cells;
  ASSERT_TRUE(bench::beamCellsForTetCount(1536, &cells));
  const bench::BeamMesh beam = bench::makeBeamMesh(cells.x, cells.y, cells.z, 4.0, 1.0, 1.0);
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(bench::beamDeformableDesc(beam, degree), &body), Status::Ok) << lastError();
  body->setPinned(beam.fixedVertices.data(), static_cast<int64_t>(beam.fixedVertices.size()), true);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.dt = 1.0 / 60.0;
  in.gravity = Vec3(0, -9.81, 0);
  in.tasks = tasks.get();
  for (int step = 0; step < 20; ++step) {
    ActorStats stats;
    body->step(in, &stats);
  }
  const gpu::ElementAssemblyView view = body->elementAssemblyView();
  std::string error;
  auto device = gpu::DeviceElementAssembly::create(view, &error);
  ASSERT_NE(device, nullptr) << error;

  std::vector<double> bent(body->positions().begin(), body->positions().end());
  std::vector<double> mirrored = bent;
  for (size_t i = 2; i < mirrored.size(); i += 3) mirrored[i] = -mirrored[i];
  std::vector<double> identity(4 * view.elements, 0.0);
  for (size_t e = 0; e < identity.size(); e += 4) identity[e] = 1.0;
  const double scale = in.dt * in.dt;
  for (const std::vector<double>* x : {&bent, &mirrored}) {
    const testref::ElementAssembly cpu = testref::elementAssembly(view, x->data(), identity, scale);
    testref::ElementAssembly onDevice;
    onDevice.quat = identity;
    onDevice.values.resize(cpu.values.size());
    onDevice.force.resize(cpu.force.size());
    ASSERT_TRUE(device->assemble(x->data(), onDevice.quat.data(), scale, onDevice.values.data(),
                                 onDevice.force.data(), &error))
        << error;
    const char* which = x == &bent ? "bent" : "mirrored";
    EXPECT_TRUE(sameBits(onDevice.quat, cpu.quat)) << which;
    EXPECT_TRUE(sameBits(onDevice.values, cpu.values)) << which;
    EXPECT_TRUE(sameBits(onDevice.force, cpu.force)) << which;
    // Not a vacuous comparison: the beam is loaded (forces not all zero) and rotated.
    double largestForce = 0.0, largestTurn = 0.0;
    for (double f : cpu.force) largestForce = std::max(largestForce, std::abs(f));
    for (size_t e = 0; e < cpu.quat.size(); e += 4) largestTurn = std::max(largestTurn, 1.0 - std::abs(cpu.quat[e]));
    EXPECT_GT(largestForce, 0.0) << which;
    EXPECT_GT(largestTurn, 1e-6) << which;
  }
}

INSTANTIATE_TEST_SUITE_P(Degrees, DeviceElementAssembly, ::testing::Values(1, 2, 3),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return std::string(param.param == 1 ? "linear" : param.param == 2 ? "quadratic" : "cubic");
                         });

}  // namespace
}  // namespace vp::gpu_test
