// Advection that leaves out what nothing reads (advection.h: FaceSkipMask, keepBeyond):
// the left-out samples keep their values exactly, and samples whose stencils never touch them
// come out as a full advection gives them.
#include <gtest/gtest.h>

#include <cmath>

#include "fluid/advection/advection.h"

namespace vp {
namespace {

MacGrid swirlingGrid(int n) {
  MacGridSpec spec;
  spec.origin = Vec3::Zero();
  spec.h = 1.0 / n;
  spec.nx = spec.ny = spec.nz = n;
  MacGrid g;
  EXPECT_EQ(initMacGrid(spec, {}, &g), Status::Ok);
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = g.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const Vec3 x = g.faceCentre(a, i, j, k);
          g.velocity[a][g.faceIndex(a, i, j, k)] = std::sin(3.0 * x[(a + 1) % 3] + a) * std::cos(2.0 * x[(a + 2) % 3]);
        }
  }
  return g;
}

TEST(FluidAdvectionSkip, SkippedFacesKeepTheirValueAndFarFacesMatchAFullAdvection) {
  const int n = 16;
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double dt = 0.5 / n;  // at most about half a cell: stencils reach 2 cells at most
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack}) {
    MacGrid full = swirlingGrid(n), skipped = full;
    const MacGrid old = full;
    // Skip every face in the upper half (y above 0.5), as a liquid's far air.
    Array<uint8_t> marks[3];
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3i d = full.faceDims(a);
      marks[a].assign(full.velocity[a].size(), 0);
      for (int k = 0; k < d.z(); ++k)
        for (int j = 0; j < d.y(); ++j)
          for (int i = 0; i < d.x(); ++i)
            if (full.faceCentre(a, i, j, k).y() > 0.5) marks[a][full.faceIndex(a, i, j, k)] = 7;
    }
    AdvectionWorkspace w1, w2;
    advectVelocity(*tasks, full, dt, scheme, w1);
    advectVelocity(*tasks, skipped, dt, scheme, w2, FaceSkipMask{marks, 7});
    int compared = 0;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3i d = full.faceDims(a);
      for (int k = 0; k < d.z(); ++k)
        for (int j = 0; j < d.y(); ++j)
          for (int i = 0; i < d.x(); ++i) {
            const size_t f = full.faceIndex(a, i, j, k);
            const double y = full.faceCentre(a, i, j, k).y();
            if (marks[a][f] == 7) {
              EXPECT_EQ(skipped.velocity[a][f], old.velocity[a][f]);
            } else if (y < 0.5 - 3.0 / n) {  // forward and backward stencils stay below 0.5
              EXPECT_EQ(skipped.velocity[a][f], full.velocity[a][f]);
              ++compared;
            }
          }
    }
    EXPECT_GT(compared, 3 * n * n * 4);
  }
}

TEST(FluidAdvectionSkip, CellsBeyondTheThresholdKeepTheirValueAndNearCellsMatch) {
  const int n = 16;
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double dt = 0.5 / n;
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack}) {
    const MacGrid g = swirlingGrid(n);
    // A plane level set, y = 0.5, clamped at 4 cells as redistancing leaves it.
    Array<double> phi(static_cast<size_t>(g.cellCount()));
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          phi[g.cellIndex(i, j, k)] = std::clamp(g.cellCentre(i, j, k).y() - 0.5, -4.0 / n, 4.0 / n);
    Array<double> full = phi, kept = phi;
    Array<double>* fullFields[1] = {&full};
    Array<double>* keptFields[1] = {&kept};
    AdvectionWorkspace w1, w2;
    const double keepBeyond = 3.0 / n;
    advectCellScalars(*tasks, g, dt, scheme, fullFields, 1, w1);
    advectCellScalars(*tasks, g, dt, scheme, keptFields, 1, w2, nullptr, nullptr, keepBeyond);
    int compared = 0;
    for (size_t c = 0; c < phi.size(); ++c) {
      if (std::abs(phi[c]) >= keepBeyond) {
        EXPECT_EQ(kept[c], phi[c]);
      } else if (std::abs(phi[c]) < keepBeyond - 2.0 / n) {  // stencils reach no kept cell
        EXPECT_EQ(kept[c], full[c]);
        ++compared;
      }
    }
    EXPECT_GE(compared, 2 * n * n);
  }
}

}  // namespace
}  // namespace vp
