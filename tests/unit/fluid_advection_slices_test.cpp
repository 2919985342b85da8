// Sliced advection (advection.h: VelocityAdvectionSlices, ScalarAdvectionSlices): however the
// passes are cut into slices (a bound per slice, which may change from slice to slice) and
// however many workers run them, the result is bitwise the whole call's, and no slice holds
// more than its bound of samples (or one row).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "fluid/advection/advection.h"

namespace vp {
namespace {

constexpr int kNx = 13, kNy = 9, kNz = 7;
constexpr int64_t kWhole = std::numeric_limits<int64_t>::max();
// One row (anything under a row's length), less than a row, a few rows, many, everything.
constexpr int64_t kSliceBounds[] = {1, 7, 40, 100, 1000, kWhole};
// 0: a bound that changes every slice (as a slab sizer shrinks and grows them).
constexpr int64_t kVarying = 0;
constexpr int64_t kBoundsToTry[] = {1, 7, 40, 100, 1000, kWhole, kVarying};

// The bound for slice n.
int64_t boundOf(int64_t bound, int n) {
  constexpr int64_t cycle[] = {1, 300, 7, 5000, 40};
  return bound != kVarying ? bound : cycle[n % 5];
}
constexpr AdvectionScheme kSchemes[] = {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack};

// A swirl about an axis through the box's middle plus a shear, on a box that is not a cube
// and not at the origin, so every axis and lattice differs.
MacGrid swirlingGrid() {
  MacGridSpec spec;
  spec.origin = Vec3(-0.3, 0.2, 0.1);
  spec.h = 0.1;
  spec.nx = kNx;
  spec.ny = kNy;
  spec.nz = kNz;
  MacGrid g;
  const std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Open, DomainSide::Wall,
                                        DomainSide::Wall, DomainSide::Open, DomainSide::Wall};
  EXPECT_EQ(initMacGrid(spec, sides, &g), Status::Ok);
  const Vec3 centre = spec.origin + 0.5 * spec.h * Vec3(kNx, kNy, kNz);
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = g.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const Vec3 r = g.faceCentre(a, i, j, k) - centre;
          const Vec3 swirl(-2.0 * r.y() + 0.3 * r.z(), 2.0 * r.x(), 0.7 * std::sin(4.0 * r.x()) - 0.3 * r.x());
          g.velocity[a][g.faceIndex(a, i, j, k)] = swirl[a] + 0.2 * std::cos(5.0 * r[(a + 1) % 3] + a);
        }
  }
  return g;
}

// A sub-step that traces about one and a half cells.
double subStep() { return 0.15 / 2.5; }

// A workspace full of NaN, larger than needed: a slice that read what no pass wrote, or a
// size that depended on what was there before, would show in the result.
AdvectionWorkspace staleWorkspace() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const size_t big = 4 * (kNx + 1) * (kNy + 1) * (kNz + 1);
  AdvectionWorkspace w;
  for (auto& v : w.advected) v.assign(big, nan);
  w.forward.assign(big, nan);
  w.rangeLo.assign(big, nan);
  w.rangeHi.assign(big, nan);
  w.traces.assign(big, Eigen::Vector3d::Constant(nan));
  w.kept.assign(big, 1);
  return w;
}

// Faces marked for skipping: those in the upper third, as a liquid's far air.
struct SkipMarks {
  Array<uint8_t> marks[3];
  static constexpr uint8_t kMark = 5;
};
SkipMarks upperThirdMarks(const MacGrid& g) {
  SkipMarks s;
  const double top = g.spec.origin.y() + g.spec.h * kNy * 2.0 / 3.0;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = g.faceDims(a);
    s.marks[a].assign(g.velocity[a].size(), 0);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i)
          if (g.faceCentre(a, i, j, k).y() > top) s.marks[a][g.faceIndex(a, i, j, k)] = SkipMarks::kMark;
  }
  return s;
}

// Open faces around a solid block of cells and a wall one cell thick with a hole.
CellOpenFaces openFacesAroundSolids(TaskSystem& tasks, const MacGrid& g) {
  FaceFractionField fractions;
  EXPECT_EQ(initFaceFractionField(g.spec, &fractions), Status::Ok);
  auto solidCell = [](int i, int j, int k) {
    const bool block = i >= 2 && i <= 4 && j >= 3 && j <= 5 && k >= 1 && k <= 3;
    const bool wall = i == 8 && !(j == 4 && k == 3);
    return block || wall;
  };
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) {
        if (!solidCell(i, j, k)) continue;
        for (int a = 0; a < 3; ++a)
          for (int high = 0; high < 2; ++high) {
            Eigen::Vector3i f(i, j, k);
            f[a] += high;
            fractions.open[a][fractions.faceIndex(a, f.x(), f.y(), f.z())] = 0.0;
          }
      }
  CellOpenFaces open;
  buildCellOpenFaces(tasks, g, fractions, &open);
  return open;
}

Array<double> cellField(const MacGrid& g, double (*value)(const Vec3&)) {
  Array<double> f(static_cast<size_t>(g.cellCount()));
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) f[g.cellIndex(i, j, k)] = value(g.cellCentre(i, j, k));
  return f;
}
double density(const Vec3& x) { return std::max(0.0, std::sin(7.0 * x.x()) * std::cos(5.0 * x.y() + x.z())); }
double temperature(const Vec3& x) { return 20.0 + 3.0 * x.y() * x.y() - 2.0 * x.x() * x.z(); }
// A sphere's distance, clamped as redistancing leaves it.
double levelSet(const Vec3& x) {
  return std::clamp((x - Vec3(0.35, 0.65, 0.45)).norm() - 0.3, -0.45, 0.45);
}

TEST(FluidAdvectionSlices, VelocityMatchesTheWholeCallForEverySlicingAndWorkerCount) {
  auto reference = TaskSystem::create(TaskHooks{}, 1);
  const MacGrid initial = swirlingGrid();
  const SkipMarks skipMarks = upperThirdMarks(initial);
  const FaceSkipMask masks[] = {FaceSkipMask{}, FaceSkipMask{skipMarks.marks, SkipMarks::kMark}};
  for (AdvectionScheme scheme : kSchemes)
    for (const FaceSkipMask& skip : masks) {
      MacGrid expected = initial;
      AdvectionWorkspace whole;
      advectVelocity(*reference, expected, subStep(), scheme, whole, skip);
      for (int workers : {1, 3}) {
        auto tasks = TaskSystem::create(TaskHooks{}, workers);
        for (int64_t bound : kBoundsToTry) {
          SCOPED_TRACE(testing::Message() << "scheme " << static_cast<int>(scheme) << " skip "
                                          << (skip.marks != nullptr) << " workers " << workers << " bound " << bound);
          MacGrid sliced = initial;
          AdvectionWorkspace work = staleWorkspace();
          VelocityAdvectionSlices slices;
          slices.prepare(*tasks, sliced, subStep(), scheme, work, skip);
          for (int n = 0; !slices.runSlice(boundOf(bound, n)); ++n)
            for (int a = 0; a < 3; ++a) ASSERT_EQ(sliced.velocity[a], initial.velocity[a]);  // until finish()
          for (int a = 0; a < 3; ++a) ASSERT_EQ(sliced.velocity[a], initial.velocity[a]);
          slices.finish();
          for (int a = 0; a < 3; ++a) EXPECT_EQ(sliced.velocity[a], expected.velocity[a]) << "axis " << a;
        }
      }
    }
}

struct ScalarCase {
  const char* name;
  bool openFaces;
  bool solidValues;
  double keepBeyond;
  int conservedField = -1;
};

TEST(FluidAdvectionSlices, ScalarsMatchTheWholeCallForEverySlicingAndWorkerCount) {
  auto reference = TaskSystem::create(TaskHooks{}, 1);
  const MacGrid grid = swirlingGrid();
  const CellOpenFaces open = openFacesAroundSolids(*reference, grid);
  const double solidValues[2] = {0.25, -3.0};
  const ScalarCase cases[] = {{"plain", false, false, 0.0},
                              {"open faces", true, false, 0.0},
                              {"open faces, solid values", true, true, 0.0},
                              {"keep beyond", false, false, 0.25},
                              {"all", true, true, 0.25},
                              {"conserved", true, true, 0.0, 0},
                              {"conserved second", false, false, 0.0, 1}};
  for (AdvectionScheme scheme : kSchemes)
    for (const ScalarCase& c : cases) {
      // With keepBeyond the first field is a level set, as a liquid's.
      const Array<double> initial[2] = {cellField(grid, c.keepBeyond > 0.0 ? levelSet : density),
                                              cellField(grid, temperature)};
      const CellOpenFaces* openFaces = c.openFaces ? &open : nullptr;
      const double* solid = c.solidValues ? solidValues : nullptr;
      Array<double> expected[2] = {initial[0], initial[1]};
      Array<double>* expectedFields[2] = {&expected[0], &expected[1]};
      AdvectionWorkspace whole;
      advectCellScalars(*reference, grid, subStep(), scheme, expectedFields, 2, whole, openFaces, solid, c.keepBeyond,
                        c.conservedField);
      ASSERT_NE(expected[0], initial[0]);
      for (int workers : {1, 3}) {
        auto tasks = TaskSystem::create(TaskHooks{}, workers);
        for (int64_t bound : kBoundsToTry) {
          SCOPED_TRACE(testing::Message() << "scheme " << static_cast<int>(scheme) << " " << c.name << " workers "
                                          << workers << " bound " << bound);
          Array<double> sliced[2] = {initial[0], initial[1]};
          AdvectionWorkspace work = staleWorkspace();
          ScalarAdvectionSlices slices;
          {
            // The object keeps its own copy of the field list: this one is gone before the slices run.
            Array<double>* fields[2] = {&sliced[0], &sliced[1]};
            slices.prepare(*tasks, grid, subStep(), scheme, fields, 2, work, openFaces, solid, c.keepBeyond,
                           c.conservedField);
          }
          for (int n = 0; !slices.runSlice(boundOf(bound, n)); ++n) {
          }
          EXPECT_EQ(sliced[0], expected[0]);
          EXPECT_EQ(sliced[1], expected[1]);
        }
      }
    }
}

TEST(FluidAdvectionSlices, NoFieldsMeansNoSlices) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  const MacGrid grid = swirlingGrid();
  AdvectionWorkspace work;
  ScalarAdvectionSlices slices;
  slices.prepare(*tasks, grid, subStep(), AdvectionScheme::MacCormack, nullptr, 0, work, nullptr, nullptr, 0.0);
  EXPECT_TRUE(slices.runSlice(1));
  EXPECT_EQ(slices.lastSliceSamples(), 0);
}

// Runs the slices, sums their samples and checks each against its bound; returns the slice
// count.
template <class Slices>
int runAndCheckSliceSizes(Slices& slices, int64_t bound, int64_t expectedSamples) {
  const int64_t longestRow = kNx + 1;
  int64_t total = 0;
  int count = 0;
  for (bool done = false; !done; ++count) {
    done = slices.runSlice(bound);
    const int64_t samples = slices.lastSliceSamples();
    EXPECT_GT(samples, 0);
    EXPECT_LE(samples, std::max(bound, longestRow)) << "slice " << count << " bound " << bound;
    if (bound < kNx) {
      EXPECT_LE(samples, longestRow) << "more than one row, slice " << count;
    }
    total += samples;
  }
  EXPECT_EQ(total, expectedSamples) << "bound " << bound;
  return count;
}

TEST(FluidAdvectionSlices, SlicesGrowInNumberAsTheirBoundShrinksAndStayWithinIt) {
  MacGrid grid = swirlingGrid();
  const int64_t faces = static_cast<int64_t>(grid.velocity[0].size() + grid.velocity[1].size() + grid.velocity[2].size());
  const int64_t cells = grid.cellCount();
  const int64_t rows[3] = {kNy * kNz, (kNy + 1) * kNz, kNy * (kNz + 1)};  // per face axis
  Array<double> a = cellField(grid, density), b = cellField(grid, temperature);
  Array<double>* fields[2] = {&a, &b};
  AdvectionWorkspace work;
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  for (AdvectionScheme scheme : kSchemes) {
    const int passes = scheme == AdvectionScheme::MacCormack ? 2 : 1;
    int previousVelocity = 0, previousScalars = 0;
    for (int64_t bound : kSliceBounds) {  // from one row to everything
      VelocityAdvectionSlices velocity;
      velocity.prepare(*tasks, grid, subStep(), scheme, work, {});
      const int velocityCount = runAndCheckSliceSizes(velocity, bound, passes * faces);
      ScalarAdvectionSlices scalars;
      scalars.prepare(*tasks, grid, subStep(), scheme, fields, 2, work, nullptr, nullptr, 0.0);
      const int scalarCount = runAndCheckSliceSizes(scalars, bound, (1 + 2 * passes) * cells);
      if (bound == 1) {  // one row per slice
        EXPECT_EQ(velocityCount, passes * (rows[0] + rows[1] + rows[2]));
        EXPECT_EQ(scalarCount, (1 + 2 * passes) * kNy * kNz);
      } else {
        EXPECT_LE(velocityCount, previousVelocity);
        EXPECT_LE(scalarCount, previousScalars);
      }
      if (bound == kWhole) {  // everything in one slice, as the whole call runs it
        EXPECT_EQ(velocityCount, 1);
        EXPECT_EQ(scalarCount, 1);
      }
      previousVelocity = velocityCount;
      previousScalars = scalarCount;
    }
  }
}

}  // namespace
}  // namespace vp
