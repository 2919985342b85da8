// The liquid's level-set upkeep and velocity extrapolation in slices (SolidExtensionRun,
// RedistanceRun, VolumeCorrectionRun, VelocityExtrapolationRun): however the passes are cut
// and however many workers run them, every array and statistic is bitwise the whole call's,
// and no slice does more than its bound of samples (one face row, for the extrapolation).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "collide/face_coverage.h"
#include "fluid/fluid_desc.h"
#include "fluid/surface/level_set_redistance.h"
#include "fluid/surface/level_set_solid_extension.h"
#include "fluid/surface/liquid_volume.h"
#include "fluid/surface/velocity_extrapolation.h"
#include "fluid_liquid_test_util.h"

namespace vp {
namespace {

constexpr int64_t kWhole = std::numeric_limits<int64_t>::max();
// One sample, a few (not a divisor of anything in the grid), a few rows' worth, everything.
constexpr int64_t kSliceBounds[] = {1, 29, 300, kWhole};
constexpr int kWorkerCounts[] = {1, 3};

template <class T>
bool sameBits(const Array<T>& a, const Array<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Advances to the end; returns the slice count. No slice may do more than `most` samples.
template <class Run>
int advanceToEnd(Run& run, int64_t most) {
  int slices = 0;
  for (bool done = false; !done;) {
    done = run.advance();
    ++slices;
    EXPECT_LE(run.lastSliceSamples(), most);
    if (slices > 10000000) {
      ADD_FAILURE() << "no end in sight";
      break;
    }
  }
  EXPECT_TRUE(run.advance());  // a finished run stays finished
  return slices;
}

// A tank with a liquid level set and a collider crossing its surface, as one step leaves it
// before the upkeep: phi a distance only up to a smooth factor, air dragged into the solid.
struct Tank {
  MacGrid grid;
  FaceFractionField fractions;
  PreparedCollider collider;
  Array<double> phi, weights;
};

template <class Sdf>
void makeTank(TaskSystem& tasks, const MacGridSpec& spec, const Sdf& liquid, const Eigen::Vector3d& sphereCentre,
              double sphereRadius, Tank* t) {
  ASSERT_EQ(initMacGrid(spec, testutil::kClosedTank, &t->grid), Status::Ok) << lastError();
  ASSERT_EQ(initFaceFractionField(spec, &t->fractions), Status::Ok) << lastError();
  ColliderShape sphere;
  sphere.kind = ShapeKind::Sphere;
  sphere.radius = sphereRadius;
  sphere.translation = sphereCentre;
  ASSERT_EQ(prepareCollider(sphere, &t->collider), Status::Ok) << lastError();
  const PreparedCollider* list[] = {&t->collider};
  ASSERT_EQ(computeFaceFractions(list, 1, &t->fractions), Status::Ok) << lastError();
  cellOpenFractions(tasks, t->fractions, &t->weights);
  t->phi = testutil::sampleCells(
      t->grid, [&](const Eigen::Vector3d& x) { return liquid(x) * (1.3 + 0.5 * std::sin(7.0 * x.x() + 2.0 * x.z())); });
  for (size_t c = 0; c < t->phi.size(); ++c)
    if (t->weights[c] < kMaxCoveredCellWeight) t->phi[c] = 0.2;
  // A velocity that differs on every face, so a face averaged from the wrong neighbours shows.
  testutil::forEachFace(t->grid, [&](int a, int i, int j, int k, size_t f) {
    const Eigen::Vector3d x = t->grid.faceCentre(a, i, j, k);
    t->grid.velocity[a][f] = std::sin(3.0 * x.x() + a) + 0.5 * std::cos(2.0 * x.y() - 5.0 * x.z());
  });
}

MacGridSpec gridSpec(double h, int nx, int ny, int nz) {
  MacGridSpec spec;
  spec.h = h;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  return spec;
}

// A small liquid: a tilted box of liquid in a 17 x 13 x 11 grid with a sphere through its top.
void makeSmallTank(TaskSystem& tasks, Tank* t) {
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.25, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  auto box = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d q =
        (turn.transpose() * (x - Eigen::Vector3d(0.5, 0.3, 0.33))).cwiseAbs() - Eigen::Vector3d(0.35, 0.2, 0.22);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
  makeTank(tasks, gridSpec(1.0 / 16.0, 17, 13, 11), box, Eigen::Vector3d(0.62, 0.47, 0.36), 0.16, t);
}

// The default scene's tank (24 x 15 x 24 cells of 1/12 m, water 0.5 m deep) with its buoy
// floating at the surface, which a wave crosses.
void makeDefaultTank(TaskSystem& tasks, Tank* t) {
  makeTank(tasks, gridSpec(1.0 / 12.0, 24, 15, 24),
           [](const Eigen::Vector3d& x) { return x.y() - 0.5 - 0.05 * std::sin(3.0 * x.x()); },
           Eigen::Vector3d(1.65, 0.5, 1.65), 0.2, t);
}

TEST(FluidLevelSetSlices, SolidExtensionIsBitwiseTheWholeCall) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  Tank t;
  makeSmallTank(*tasks, &t);
  Array<double> whole = t.phi;
  Array<int64_t> wholeScratch;
  extendLevelSetIntoSolids(t.grid.spec, t.weights, whole, wholeScratch);
  ASSERT_FALSE(sameBits(whole, t.phi));  // there was something to extend
  int64_t solid = 0;
  for (double w : t.weights) solid += w < kMaxCoveredCellWeight;
  Array<int64_t> scratch{1, 2, 3};  // stale: a run must not read what is there
  for (int64_t bound : kSliceBounds) {
    SCOPED_TRACE(bound);
    Array<double> phi = t.phi;
    SolidExtensionRun run;
    ASSERT_EQ(run.prepare(t.grid.spec, t.weights, phi, scratch, bound), Status::Ok) << lastError();
    const int slices = advanceToEnd(run, bound);
    EXPECT_TRUE(sameBits(phi, whole));
    EXPECT_TRUE(sameBits(scratch, wholeScratch));
    if (bound == 1) {
      EXPECT_GE(slices, t.grid.cellCount() + solid);
    }
    if (bound == kWhole) {
      EXPECT_EQ(slices, 1);
    }
  }
  SolidExtensionRun bad;
  Array<double> shortPhi(7, 0.0);
  EXPECT_EQ(bad.prepare(t.grid.spec, t.weights, shortPhi, scratch, 100), Status::InvalidArgument);
  EXPECT_TRUE(bad.advance());
  EXPECT_EQ(bad.prepare(t.grid.spec, t.weights, t.phi, scratch, 0), Status::InvalidArgument);
}

void expectSameStats(const RedistanceStats& a, const RedistanceStats& b) {
  EXPECT_EQ(a.surfaceCells, b.surfaceCells);
  EXPECT_EQ(a.bandCells, b.bandCells);
  EXPECT_EQ(a.sweeps, b.sweeps);
  EXPECT_EQ(a.converged, b.converged);
}

TEST(FluidLevelSetSlices, RedistanceIsBitwiseTheWholeCall) {
  auto one = TaskSystem::create(TaskHooks{}, 1);
  Tank t;
  makeSmallTank(*one, &t);
  Array<int64_t> scratch;
  extendLevelSetIntoSolids(t.grid.spec, t.weights, t.phi, scratch);
  Array<double> whole = t.phi;
  RedistanceWorkspace workspace;  // shared by every run below, so each finds the last one's leftovers
  RedistanceStats wholeStats;
  ASSERT_EQ(redistanceLevelSet(*one, t.grid.spec, whole.data(), RedistanceSettings{}, workspace, &wholeStats),
            Status::Ok);
  EXPECT_GT(wholeStats.sweeps, 2);
  EXPECT_GT(wholeStats.bandCells, 2 * wholeStats.surfaceCells);
  for (int workers : kWorkerCounts) {
    auto tasks = TaskSystem::create(TaskHooks{}, workers);
    for (int64_t bound : kSliceBounds) {
      SCOPED_TRACE(testing::Message() << workers << " workers, bound " << bound);
      Array<double> phi = t.phi;
      RedistanceRun run;
      ASSERT_EQ(run.prepare(*tasks, t.grid.spec, phi.data(), RedistanceSettings{}, workspace, bound), Status::Ok);
      const int slices = advanceToEnd(run, bound);
      EXPECT_TRUE(sameBits(phi, whole));
      expectSameStats(run.stats(), wholeStats);
      if (bound == 1) {
        EXPECT_GT(slices, 2 * t.grid.cellCount() + wholeStats.sweeps * wholeStats.bandCells);
      }
      if (bound == kWhole) {
        EXPECT_EQ(slices, 1);
      }
    }
  }
  RedistanceRun bad;
  EXPECT_EQ(bad.prepare(*one, t.grid.spec, nullptr, RedistanceSettings{}, workspace, 100), Status::InvalidArgument);
  EXPECT_TRUE(bad.advance());
  EXPECT_EQ(bad.prepare(*one, t.grid.spec, t.phi.data(), RedistanceSettings{}, workspace, 0),
            Status::InvalidArgument);
}

void expectSameResult(const VolumeCorrectionResult& a, const VolumeCorrectionResult& b) {
  EXPECT_TRUE(sameBits(a.shift, b.shift));
  EXPECT_TRUE(sameBits(a.volumeBefore, b.volumeBefore));
  EXPECT_TRUE(sameBits(a.volumeAfter, b.volumeAfter));
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.converged, b.converged);
}

// Every slice bound on 1 and 3 workers against the whole call on 1; returns the slice counts
// on 1 worker, per bound.
std::vector<int> expectCorrectionInSlices(const MacGridSpec& spec, const Array<double>& input,
                                          const double* weights, double target, const int64_t* bounds, int boundCount,
                                          VolumeCorrectionResult* wholeResult) {
  auto one = TaskSystem::create(TaskHooks{}, 1);
  Array<double> whole = input;
  EXPECT_EQ(correctLiquidVolume(*one, spec, whole.data(), weights, target, VolumeCorrectionSettings{}, wholeResult),
            Status::Ok);
  std::vector<int> counts;
  VolumeCorrectionRun run;  // kept from run to run, as an actor keeps it from step to step
  for (int workers : kWorkerCounts) {
    auto tasks = TaskSystem::create(TaskHooks{}, workers);
    for (int b = 0; b < boundCount; ++b) {
      SCOPED_TRACE(testing::Message() << workers << " workers, bound " << bounds[b]);
      Array<double> phi = input;
      EXPECT_EQ(run.prepare(*tasks, spec, phi.data(), weights, target, VolumeCorrectionSettings{}, bounds[b]),
                Status::Ok);
      const int slices = advanceToEnd(run, bounds[b]);
      if (workers == 1) counts.push_back(slices);
      EXPECT_TRUE(sameBits(phi, whole));
      expectSameResult(run.result(), *wholeResult);
    }
  }
  return counts;
}

TEST(FluidLevelSetSlices, VolumeCorrectionIsBitwiseTheWholeCall) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  Tank t;
  makeSmallTank(*tasks, &t);
  RedistanceWorkspace workspace;
  ASSERT_EQ(redistanceLevelSet(*tasks, t.grid.spec, t.phi.data(), RedistanceSettings{}, workspace, nullptr),
            Status::Ok);
  const double volume = liquidVolume(*tasks, t.grid.spec, t.phi.data(), t.weights.data());
  VolumeCorrectionResult whole;
  // A small deficit: a few Newton steps.
  const std::vector<int> counts = expectCorrectionInSlices(t.grid.spec, t.phi, t.weights.data(), 1.02 * volume,
                                                           kSliceBounds, 4, &whole);
  EXPECT_TRUE(whole.converged);
  EXPECT_GE(whole.iterations, 2);
  EXPECT_GT(counts[0], 2 * t.grid.cellCount());
  EXPECT_EQ(counts[3], 1);
  // Beyond the shift limit (bisection steps), and without weights.
  expectCorrectionInSlices(t.grid.spec, t.phi, t.weights.data(), 3.0 * volume, kSliceBounds, 4, &whole);
  EXPECT_FALSE(whole.converged);
  expectCorrectionInSlices(t.grid.spec, t.phi, nullptr, 0.97 * volume, kSliceBounds, 4, &whole);
  EXPECT_TRUE(whole.converged);
  VolumeCorrectionRun bad;
  EXPECT_EQ(bad.prepare(*tasks, t.grid.spec, t.phi.data(), nullptr, -1.0, VolumeCorrectionSettings{}, 100),
            Status::InvalidArgument);
  EXPECT_TRUE(bad.advance());
  EXPECT_EQ(bad.prepare(*tasks, t.grid.spec, t.phi.data(), nullptr, volume, VolumeCorrectionSettings{}, 0),
            Status::InvalidArgument);
}

// The sums run over fixed chunks of 8192 entries; on a wide flat tank both the cells and the
// band span several, so slabs end inside chunks and chunks end inside slabs.
TEST(FluidLevelSetSlices, VolumeSumsCutInsideTheirChunksAreBitwiseTheWholeCall) {
  const MacGridSpec spec = gridSpec(1.0 / 64.0, 64, 20, 64);
  MacGrid grid;
  ASSERT_EQ(initMacGrid(spec, testutil::kClosedTank, &grid), Status::Ok);
  const Array<double> phi = testutil::sampleCells(grid, [](const Eigen::Vector3d& x) {
    return x.y() - 0.15 - 0.03 * std::sin(9.0 * x.x()) * std::cos(7.0 * x.z());
  });
  int64_t band = 0;  // cells a shift within the limit can change: |phi| < (1.5 + 1) h
  for (double p : phi) band += std::fabs(p) < 2.5 * spec.h;
  ASSERT_GT(band, 2 * 8192);
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  const double volume = liquidVolume(*tasks, spec, phi.data(), nullptr);
  const int64_t bounds[] = {777, 8192, 12345, kWhole};
  VolumeCorrectionResult whole;
  expectCorrectionInSlices(spec, phi, nullptr, 1.01 * volume, bounds, 4, &whole);
  EXPECT_TRUE(whole.converged);
  EXPECT_GE(whole.iterations, 1);
}

void expectSameVelocities(const MacGrid& a, const MacGrid& b) {
  for (int axis = 0; axis < 3; ++axis) EXPECT_TRUE(sameBits(a.velocity[axis], b.velocity[axis])) << "axis " << axis;
}

TEST(FluidLevelSetSlices, VelocityExtrapolationIsBitwiseTheWholeCall) {
  auto one = TaskSystem::create(TaskHooks{}, 1);
  Tank t;
  makeSmallTank(*one, &t);
  VelocityExtrapolationSettings settingsList[3];
  settingsList[0].layers = 4;  // as the actor extrapolates
  settingsList[0].minSourceOpenFraction = 0.25;
  settingsList[0].zeroUnreached = true;
  settingsList[1].layers = 2;
  settingsList[1].intoClosedFaces = true;
  settingsList[2].layers = 0;
  VelocityExtrapolationState marks;  // shared, so each run finds the last one's leftovers
  for (const VelocityExtrapolationSettings& settings : settingsList) {
    SCOPED_TRACE(testing::Message() << settings.layers << " layers");
    MacGrid whole = t.grid;
    ASSERT_EQ(extrapolateVelocity(*one, whole, t.fractions, t.phi.data(), settings, marks), Status::Ok);
    const VelocityExtrapolationState wholeMarks = marks;
    int64_t faces = 0, rows = 0, zeroed = 0;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3i d = t.grid.faceDims(a);
      faces += static_cast<int64_t>(d.prod());
      rows += static_cast<int64_t>(d.y()) * d.z();
      for (size_t f = 0; f < whole.velocity[a].size(); ++f) zeroed += wholeMarks.mark[a][f] == kExtrapolationUnreached;
    }
    if (settings.layers > 0) {
      EXPECT_GT(zeroed, 0);  // the zeroing has work to do
    }
    for (int workers : kWorkerCounts) {
      auto tasks = TaskSystem::create(TaskHooks{}, workers);
      for (int64_t bound : kSliceBounds) {
        SCOPED_TRACE(testing::Message() << workers << " workers, bound " << bound);
        MacGrid grid = t.grid;
        VelocityExtrapolationRun run;
        ASSERT_EQ(run.prepare(*tasks, grid, t.fractions, t.phi.data(), settings, marks, bound), Status::Ok);
        // Rows are 17 or 18 faces, so a bound of one sample still runs a row per slice.
        const int slices = advanceToEnd(run, std::max<int64_t>(bound, t.grid.spec.nx + 1));
        expectSameVelocities(grid, whole);
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(sameBits(marks.mark[a], wholeMarks.mark[a])) << "axis " << a;
        if (bound == 1) {
      EXPECT_GE(slices, rows * (1 + settings.layers));
    }
        if (bound == kWhole) {
        EXPECT_EQ(slices, 1);
      }
        if (bound == 29) {
      EXPECT_GE(slices, faces / 29);
    }
      }
    }
  }
  // zeroUnreached is the whole call followed by zeroing the faces left unreached.
  MacGrid zeroedHere = t.grid, zeroedByRun = t.grid;
  VelocityExtrapolationSettings settings = settingsList[0];
  settings.zeroUnreached = false;
  ASSERT_EQ(extrapolateVelocity(*one, zeroedHere, t.fractions, t.phi.data(), settings, marks), Status::Ok);
  for (int a = 0; a < 3; ++a)
    for (size_t f = 0; f < zeroedHere.velocity[a].size(); ++f)
      if (marks.mark[a][f] == kExtrapolationUnreached) zeroedHere.velocity[a][f] = 0.0;
  ASSERT_EQ(extrapolateVelocity(*one, zeroedByRun, t.fractions, t.phi.data(), settingsList[0], marks), Status::Ok);
  expectSameVelocities(zeroedByRun, zeroedHere);
  VelocityExtrapolationRun bad;
  EXPECT_EQ(bad.prepare(*one, t.grid, t.fractions, nullptr, settings, marks, 100), Status::InvalidArgument);
  EXPECT_TRUE(bad.advance());
  EXPECT_EQ(bad.prepare(*one, t.grid, t.fractions, t.phi.data(), settings, marks, 0), Status::InvalidArgument);
}

// The actor's upkeep: the three runs prepared together before any of them runs (prepare reads
// no values), then advanced one after the other, against the three whole calls.
struct Upkeep {
  SolidExtensionRun extension;
  RedistanceRun redistance;
  VolumeCorrectionRun correction;
  int slices[3] = {0, 0, 0};
};

void runUpkeep(TaskSystem& tasks, const Tank& t, double target, int64_t bound, Array<double>& phi,
               RedistanceWorkspace& workspace, Upkeep* u) {
  Array<int64_t> scratch;
  ASSERT_EQ(u->extension.prepare(t.grid.spec, t.weights, phi, scratch, bound), Status::Ok);
  ASSERT_EQ(u->redistance.prepare(tasks, t.grid.spec, phi.data(), RedistanceSettings{}, workspace, bound),
            Status::Ok);
  ASSERT_EQ(u->correction.prepare(tasks, t.grid.spec, phi.data(), t.weights.data(), target,
                                  VolumeCorrectionSettings{}, bound),
            Status::Ok);
  u->slices[0] = advanceToEnd(u->extension, bound);
  u->slices[1] = advanceToEnd(u->redistance, bound);
  u->slices[2] = advanceToEnd(u->correction, bound);
}

TEST(FluidLevelSetSlices, UpkeepPreparedTogetherIsBitwiseTheWholeCalls) {
  auto one = TaskSystem::create(TaskHooks{}, 1), three = TaskSystem::create(TaskHooks{}, 3);
  Tank t;
  makeSmallTank(*one, &t);
  const double target = 1.01 * liquidVolume(*one, t.grid.spec, t.phi.data(), t.weights.data());
  Array<double> whole = t.phi;
  Array<int64_t> scratch;
  RedistanceWorkspace workspace;
  extendLevelSetIntoSolids(t.grid.spec, t.weights, whole, scratch);
  ASSERT_EQ(redistanceLevelSet(*one, t.grid.spec, whole.data(), RedistanceSettings{}, workspace, nullptr), Status::Ok);
  ASSERT_EQ(correctLiquidVolume(*one, t.grid.spec, whole.data(), t.weights.data(), target, VolumeCorrectionSettings{},
                                nullptr),
            Status::Ok);
  Array<double> phi = t.phi;
  Upkeep u;
  runUpkeep(*three, t, target, 29, phi, workspace, &u);
  EXPECT_TRUE(sameBits(phi, whole));
}

// What the default scene's tank costs in slices at the default bound (printed), and that a
// bound below a pass's length splits it.
TEST(FluidLevelSetSlices, SliceCountsOfTheDefaultTank) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  Tank t;
  makeDefaultTank(*tasks, &t);
  const double target = liquidVolume(*tasks, t.grid.spec, t.phi.data(), t.weights.data());
  const int64_t bound = FluidSolverSettings{}.samplesPerSlice;
  RedistanceWorkspace workspace;
  for (int64_t b : {bound, bound / 16}) {
    Array<double> phi = t.phi;
    Upkeep u;
    runUpkeep(*tasks, t, target, b, phi, workspace, &u);
    MacGrid grid = t.grid;
    VelocityExtrapolationSettings settings;
    settings.layers = 4;
    settings.minSourceOpenFraction = 0.25;
    settings.zeroUnreached = true;
    VelocityExtrapolationState marks;
    VelocityExtrapolationRun extrapolation;
    ASSERT_EQ(extrapolation.prepare(*tasks, grid, t.fractions, phi.data(), settings, marks, b), Status::Ok);
    const int extrapolationSlices = advanceToEnd(extrapolation, b);
    const RedistanceStats& rs = u.redistance.stats();
    std::printf("    24x15x24 at %lld samples per slice: extension %d, redistance %d (%lld surface, %lld band cells, "
                "%d sweeps), volume correction %d (%d iterations), extrapolation %d slices\n",
                static_cast<long long>(b), u.slices[0], u.slices[1], static_cast<long long>(rs.surfaceCells),
                static_cast<long long>(rs.bandCells), rs.sweeps, u.slices[2], u.correction.result().iterations,
                extrapolationSlices);
    if (b < bound) {
      EXPECT_GT(u.slices[1], 2 * t.grid.cellCount() / b);
      EXPECT_GT(extrapolationSlices, 2 * t.grid.cellCount() / b);
    }
  }
}

}  // namespace
}  // namespace vp
