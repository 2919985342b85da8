// Linear-tet corotation and assembly on the device (gpu::DeviceLinearTetAssembly) against the
// same kernel bodies run by a CPU loop, as DeformableBody::corotateAndAssemble runs them. The
// device file is built with --fmad=false and the bodies use only correctly rounded operations
// (+, −, ×, ÷, sqrt), so every rotation, block and force must be the CPU's bits. ctest label
// gpu; skipped by name without a device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "beam_mesh.h"
#include "deform/deformable_body.h"
#include "deform_beam_desc.h"
#include "gpu_kernels/device_linear_tet_assembly.h"
#include "gpu_kernels/device_query.h"
#include "gpu_kernels/linear_tet_kernels.h"

namespace vp::gpu_test {
namespace {

class DeviceLinearTetAssembly : public ::testing::Test {
 protected:
  void SetUp() override {
    if (gpu::cudaDeviceCount() == 0) GTEST_SKIP() << "no CUDA device on this machine";
  }
};

struct Assembly {
  std::vector<double> quat, values, force;
};

// The CPU's two passes over the kernel bodies.
Assembly cpuAssembly(const gpu::LinearTetAssemblyView& m, const double* x, std::vector<double> quat, double scale) {
  Assembly out;
  out.quat = std::move(quat);
  std::vector<double> elementForce(12 * m.elements), rotatedGrad(12 * m.elements);
  for (int64_t e = 0; e < m.elements; ++e) {
    double corners[12];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) corners[3 * a + i] = x[3 * m.elementNodes[4 * e + a] + i];
    kernels::corotateLinearTet(corners, &m.restGradients[12 * e], m.restVolume[e], m.lambda, m.mu, &out.quat[4 * e],
                               &elementForce[12 * e], &rotatedGrad[12 * e]);
  }
  out.values.resize(9 * static_cast<size_t>(m.rowStart[m.nodes]));
  out.force.resize(3 * static_cast<size_t>(m.nodes));
  const auto addBlock = [&](int64_t e, int a, int b, double* block) {
    kernels::addLinearTetBlock(&rotatedGrad[12 * e], &m.restGradients[12 * e], a, b, m.restVolume[e], m.lambda, m.mu,
                               scale, block);
  };
  for (int64_t i = 0; i < m.nodes; ++i)
    kernels::gatherElementRow(i, 4, m.rowStart, m.incidence, m.scatter, elementForce.data(), addBlock,
                              out.values.data(), out.force.data());
  return out;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// The 12288-tet beam after 20 steps of sag, its rotations restarted from the identity (so every
// element iterates), and the same beam mirrored through z = 0 (every element inverted: the SVD
// path).
TEST_F(DeviceLinearTetAssembly, ABentAndAnInvertedBeamGiveTheCpuBits) {
  bench::BeamCells cells;
  ASSERT_TRUE(bench::beamCellsForTetCount(12288, &cells));
  const bench::BeamMesh beam = bench::makeBeamMesh(cells.x, cells.y, cells.z, 4.0, 1.0, 1.0);
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(bench::beamDeformableDesc(beam, 1), &body), Status::Ok) << lastError();
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
  const gpu::LinearTetAssemblyView view = body->linearTetAssemblyView();
  std::string error;
  auto device = gpu::DeviceLinearTetAssembly::create(view, &error);
  ASSERT_NE(device, nullptr) << error;

  std::vector<double> bent(body->positions().begin(), body->positions().end());
  std::vector<double> mirrored = bent;
  for (size_t i = 2; i < mirrored.size(); i += 3) mirrored[i] = -mirrored[i];
  std::vector<double> identity(4 * view.elements, 0.0);
  for (size_t e = 0; e < identity.size(); e += 4) identity[e] = 1.0;
  const double scale = in.dt * in.dt;
  for (const std::vector<double>* x : {&bent, &mirrored}) {
    const Assembly cpu = cpuAssembly(view, x->data(), identity, scale);
    Assembly gpu;
    gpu.quat = identity;
    gpu.values.resize(cpu.values.size());
    gpu.force.resize(cpu.force.size());
    ASSERT_TRUE(device->assemble(x->data(), gpu.quat.data(), scale, gpu.values.data(), gpu.force.data(), &error))
        << error;
    const char* which = x == &bent ? "bent" : "mirrored";
    EXPECT_TRUE(sameBits(gpu.quat, cpu.quat)) << which;
    EXPECT_TRUE(sameBits(gpu.values, cpu.values)) << which;
    EXPECT_TRUE(sameBits(gpu.force, cpu.force)) << which;
    // Not a vacuous comparison: the beam is loaded (forces not all zero) and rotated.
    double largestForce = 0.0, largestTurn = 0.0;
    for (double f : cpu.force) largestForce = std::max(largestForce, std::abs(f));
    for (size_t e = 0; e < cpu.quat.size(); e += 4) largestTurn = std::max(largestTurn, 1.0 - std::abs(cpu.quat[e]));
    EXPECT_GT(largestForce, 0.0) << which;
    EXPECT_GT(largestTurn, 1e-6) << which;
  }
}

}  // namespace
}  // namespace vp::gpu_test
