// A deformable whose implicit solves run on the CUDA device against the same deformable on the
// CPU, and the world's device choice (ctest label gpu; skipped by name without a device).
#include <gtest/gtest.h>

#include <cmath>

#include "beam_mesh.h"
#include "deform/deformable_body.h"
#include "deform_beam_desc.h"
#include "gpu_kernels/device_query.h"
#include "world.h"

namespace vp::gpu_test {
namespace {

class DeviceDeformable : public ::testing::Test {
 protected:
  void SetUp() override {
    if (gpu::cudaDeviceCount() == 0) GTEST_SKIP() << "no CUDA device on this machine";
  }
};

struct BeamTip {
  double dy = 0;
  bool onDevice = false;
  int maxIterations = 0;
};

// 60 steps of 1/60 s of the 12288-tet beam, every solve to 1e-10.
BeamTip sixtySteps(bool onDevice) {
  bench::BeamCells cells;
  EXPECT_TRUE(bench::beamCellsForTetCount(12288, &cells));
  const bench::BeamMesh beam = bench::makeBeamMesh(cells.x, cells.y, cells.z, 4.0, 1.0, 1.0);
  DeformableDesc desc = bench::beamDeformableDesc(beam, 1);
  desc.solver.tolerance = 1e-10;
  desc.solver.maxIterations = 20000;
  std::unique_ptr<DeformableBody> body;
  EXPECT_EQ(DeformableBody::create(std::move(desc), &body), Status::Ok) << lastError();
  body->setPinned(beam.fixedVertices.data(), static_cast<int64_t>(beam.fixedVertices.size()), true);
  if (onDevice) {
    EXPECT_EQ(body->setSolveOnDevice(true), Status::Ok) << lastError();
  }
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.dt = 1.0 / 60.0;
  in.gravity = Vec3(0, -9.81, 0);
  in.tasks = tasks.get();
  const double y0 = body->positions()[3 * beam.tipVertex + 1];
  BeamTip tip;
  tip.onDevice = true;
  for (int step = 0; step < 60; ++step) {
    ActorStats stats;
    body->step(in, &stats);
    tip.onDevice = tip.onDevice && stats.onDevice;
    tip.maxIterations = std::max(tip.maxIterations, stats.phase(Phase::Solve).iterations);
  }
  tip.dy = body->positions()[3 * beam.tipVertex + 1] - y0;
  return tip;
}

// Both solve every step to 1e-10 (the CPU with its multigrid, the device with block-Jacobi):
// the velocities differ by at most about the condition number times that, far below the
// tip's 1e-6 relative agreement asked for here, over 60 steps of a 4 cm sag.
TEST_F(DeviceDeformable, ABeamSolvedOnTheDeviceFollowsTheCpuFor60Steps) {
  const BeamTip cpu = sixtySteps(false);
  const BeamTip device = sixtySteps(true);
  EXPECT_FALSE(cpu.onDevice);
  EXPECT_TRUE(device.onDevice);
  EXPECT_LT(device.maxIterations, 20000) << "every device solve converged";
  EXPECT_LT(cpu.dy, -0.01);
  EXPECT_NEAR(device.dy, cpu.dy, 1e-6 * std::abs(cpu.dy));
  std::printf("tip dy: cpu %.9f m, device %.9f m\n", cpu.dy, device.dy);
}

TEST_F(DeviceDeformable, AWorldOnTheDeviceSolvesItsDeformablesThereAndSaysSo) {
  WorldConfig config;
  config.device = ComputeDevice::Cuda;
  std::unique_ptr<World> world;
  ASSERT_EQ(World::create(config, &world), Status::Ok) << lastError();
  bench::BeamCells cells;
  ASSERT_TRUE(bench::beamCellsForTetCount(1536, &cells));
  const bench::BeamMesh beam = bench::makeBeamMesh(cells.x, cells.y, cells.z, 4.0, 1.0, 1.0);
  DeformableHandle handle;
  ASSERT_EQ(world->createDeformable(bench::beamDeformableDesc(beam, 1), &handle), Status::Ok) << lastError();
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok) << lastError();
  bool found = false;
  for (const ActorStats& a : world->lastStats().actors)
    if (a.kind == ActorKind::Deformable) {
      found = true;
      EXPECT_TRUE(a.onDevice);
    }
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace vp::gpu_test
