// Multigrid updates (poisson_multigrid.h, changed_rows.h): levels brought up to date from the
// rows of the fine operator that changed equal levels rebuilt from scratch, bit for bit, while
// a collider moves, the free surface moves everywhere, nothing changes, the settings change,
// and updates are stopped between slices and started again on newer input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "fluid_pressure_scenes.h"

namespace vp {
namespace {

using testscene::sphere;

// Odd and even counts on different axes: coarse cells with one child along an axis.
constexpr int kNx = 37, kNy = 30, kNz = 27;

template <class A, class B>
void expectSameBits(const A& a, const B& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  if (a.empty()) return;  // (an empty array's data() may be null, which memcmp must not get)
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0]))) << what << " differs";
}

void expectSameLevel(const CutCellPoisson& a, const CutCellPoisson& b, const std::string& level) {
  for (int axis = 0; axis < 3; ++axis) {
    expectSameBits(a.coupling[axis], b.coupling[axis], level + " coupling " + std::to_string(axis));
    expectSameBits(a.openFraction[axis], b.openFraction[axis], level + " openFraction " + std::to_string(axis));
  }
  expectSameBits(a.diagonal, b.diagonal, level + " diagonal");
  expectSameBits(a.rowSpan, b.rowSpan, level + " rowSpan");
  expectSameBits(a.region, b.region, level + " region");
  expectSameBits(a.regionFloating, b.regionFloating, level + " regionFloating");
  expectSameBits(a.regionCellCount, b.regionCellCount, level + " regionCellCount");
  EXPECT_EQ(a.fluidCellCount, b.fluidCellCount) << level;
  expectSameBits(a.liquidPhi, b.liquidPhi, level + " liquidPhi");
  expectSameBits(a.surfaceDirichlet, b.surfaceDirichlet, level + " surfaceDirichlet");
}

void expectSameMultigrid(const PoissonMultigrid& updated, const PoissonMultigrid& rebuilt) {
  ASSERT_EQ(updated.levelCount(), rebuilt.levelCount());
  for (int l = 0; l < updated.levelCount(); ++l) {
    const std::string level = "level " + std::to_string(l);
    if (l > 0) {
      expectSameLevel(updated.coarse[static_cast<size_t>(l - 1)], rebuilt.coarse[static_cast<size_t>(l - 1)], level);
      EXPECT_EQ(updated.coarseFloating[static_cast<size_t>(l - 1)], rebuilt.coarseFloating[static_cast<size_t>(l - 1)]);
      expectSameBits(updated.prolongScale[static_cast<size_t>(l - 1)], rebuilt.prolongScale[static_cast<size_t>(l - 1)],
                     level + " prolongScale (to it from level " + std::to_string(l - 1) + ")");
    }
    const PoissonCoefficients<float>& a = updated.single[static_cast<size_t>(l)];
    const PoissonCoefficients<float>& b = rebuilt.single[static_cast<size_t>(l)];
    for (int axis = 0; axis < 3; ++axis)
      expectSameBits(a.coupling[axis], b.coupling[axis], level + " single coupling " + std::to_string(axis));
    expectSameBits(a.diagonal, b.diagonal, level + " single diagonal");
    expectSameBits(a.rowSpan, b.rowSpan, level + " single rowSpan");
    const BoundaryCellLists& la = updated.boundaryCells[static_cast<size_t>(l)];
    const BoundaryCellLists& lb = rebuilt.boundaryCells[static_cast<size_t>(l)];
    for (int colour = 0; colour < 2; ++colour)
      expectSameBits(la.byColour[static_cast<size_t>(colour)], lb.byColour[static_cast<size_t>(colour)],
                     level + " boundary cells of colour " + std::to_string(colour));
    expectSameBits(la.reads, lb.reads, level + " boundary reads");
  }
}

// The scene at time t: a sphere moving about a cell per step beside a static slanted plate;
// for a liquid, a surface that rises and a ripple that travels, so the level set changes in
// every cell; `frozen` repeats the previous time's input.
struct MovingScene {
  MacGrid grid;
  FaceFractionField fractions;
  std::vector<double> phi;
  bool liquid;

  explicit MovingScene(bool liquidScene) : liquid(liquidScene) {
    MacGridSpec spec;
    spec.h = 1.0 / 32.0;
    spec.nx = kNx, spec.ny = kNy, spec.nz = kNz;
    const std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                          DomainSide::Open, DomainSide::Wall, DomainSide::Wall};
    EXPECT_EQ(initMacGrid(spec, sides, &grid), Status::Ok);
    EXPECT_EQ(initFaceFractionField(spec, &fractions), Status::Ok);
  }

  // The sphere at time t, the surface at time surfaceT; airLift: the level set of the air more
  // than two cells from the surface rises by that many cells (as redistancing moves it), which
  // changes no fine operator value but the coarse levels' means there.
  void setTime(double t, double surfaceT, double airLift = 0.0) {
    PreparedCollider plate, ball;
    ASSERT_EQ(prepareCollider(testscene::slantedPlate(), &plate), Status::Ok);
    ASSERT_EQ(prepareCollider(sphere(Eigen::Vector3d(0.45 + 0.03 * t, 0.45, 0.42), 0.14), &ball), Status::Ok);
    const PreparedCollider* list[2] = {&plate, &ball};
    ASSERT_EQ(computeFaceFractions(list, 2, &fractions), Status::Ok);
    if (!liquid) return;
    phi.resize(static_cast<size_t>(grid.cellCount()));
    for (int k = 0; k < kNz; ++k)
      for (int j = 0; j < kNy; ++j)
        for (int i = 0; i < kNx; ++i) {
          const Eigen::Vector3d x = grid.cellCentre(i, j, k);
          const double d =
              x.y() - (0.55 + 0.004 * surfaceT) + 0.02 * std::sin(6.0 * x.x() + 0.7 * surfaceT) * std::cos(5.0 * x.z());
          phi[grid.cellIndex(i, j, k)] = d > 2.0 * grid.spec.h ? d + airLift * grid.spec.h : d;
        }
  }
  const double* liquidPhi() const { return liquid ? phi.data() : nullptr; }
};

struct Tracked {
  CutCellPoisson fine;
  ChangedRows changed;
  PoissonMultigrid mg;
};

// The fine operator and the multigrid update as one list of passes, as a projection's setup
// runs them (pressure_projection.h).
void appendUpdate(const MovingScene& scene, const MultigridSettings& settings, Tracked* t, SlabPasses* passes) {
  appendBuildCutCellPoisson(scene.grid, scene.fractions, &t->fine, scene.liquidPhi(), passes, &t->changed);
  appendBuildPoissonMultigrid(t->fine, scene.grid.sides, settings, &t->mg, passes, &t->changed);
}

void expectSameAsRebuilt(TaskSystem& tasks, const MovingScene& scene, const MultigridSettings& settings,
                         const Tracked& t) {
  CutCellPoisson fine;
  ASSERT_EQ(buildCutCellPoisson(tasks, scene.grid, scene.fractions, &fine, scene.liquidPhi()), Status::Ok);
  expectSameLevel(t.fine, fine, "fine");
  PoissonMultigrid rebuilt;
  ASSERT_EQ(buildPoissonMultigrid(tasks, fine, scene.grid.sides, settings, &rebuilt), Status::Ok);
  expectSameMultigrid(t.mg, rebuilt);
}

int64_t raisedRows(const ChangedRows& c) {
  int64_t n = 0;
  for (uint8_t f : c.row) n += f;
  return n;
}

// Every face row has one owning cell row, and that row lists it among the rows it owns (and
// no row lists a face row it does not own).
TEST(FluidMultigridChangedRows, OwnedFaceRowsInvertOwningRow) {
  constexpr int64_t ny = 3, nz = 2;
  for (int a = 0; a < 3; ++a) {
    const int64_t faceRows = (ny + (a == 1)) * (nz + (a == 2));
    std::vector<int> listed(static_cast<size_t>(faceRows), 0);
    for (int64_t row = 0; row < ny * nz; ++row) {
      const OwnedFaceRows owned = ownedFaceRows(a, row, ny, nz);
      for (int r = 0; r < owned.count; ++r) {
        ASSERT_GE(owned.row[r], 0);
        ASSERT_LT(owned.row[r], faceRows);
        EXPECT_EQ(owningRow(a, owned.row[r], ny, nz), row) << "axis " << a << " face row " << owned.row[r];
        ++listed[static_cast<size_t>(owned.row[r])];
      }
    }
    for (int64_t f = 0; f < faceRows; ++f) EXPECT_EQ(listed[static_cast<size_t>(f)], 1) << "axis " << a << " row " << f;
  }
}

class FluidMultigridUpdate : public testing::TestWithParam<bool> {};

TEST_P(FluidMultigridUpdate, UpdatedLevelsEqualRebuiltOnesBitForBit) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  MovingScene scene(GetParam());
  MultigridSettings settings;
  Tracked t;
  for (int step = 0; step < 11; ++step) {
    SCOPED_TRACE(testing::Message() << (GetParam() ? "liquid" : "smoke") << " step " << step);
    // Step 5 repeats step 4's input: an update with nothing to do; step 10 moves only the
    // level set of the air away from the surface.
    const double time = step == 5 ? 4.0 : step == 10 ? 9.0 : step;
    scene.setTime(time, time, step == 10 ? 0.5 : 0.0);
    if (step == 8) settings.boundarySweeps = 8;  // other settings: a rebuild
    if (step == 3 || step == 6) {
      // A setup stopped partway (early at step 3, late at step 6), then started again on the
      // next step's input: the flags it has not consumed must carry over.
      SlabPasses stopped(*tasks);
      appendUpdate(scene, settings, &t, &stopped);
      for (int slice = 0; slice < (step == 3 ? 3 : 40); ++slice) ASSERT_FALSE(stopped.runSlice(4000));
      continue;
    }
    SlabPasses fine(*tasks);
    appendBuildCutCellPoisson(scene.grid, scene.fractions, &t.fine, scene.liquidPhi(), &fine, &t.changed);
    fine.runAll();
    const int64_t rows = int64_t{kNy} * kNz;
    if (step == 0) {
      EXPECT_TRUE(t.changed.all);
    } else if (step != 4 && step != 7) {  // after a stopped setup the stopped one's flags are up too
      // The update path is the one under test: a part of the rows, not all.
      EXPECT_FALSE(t.changed.all);
      EXPECT_LT(raisedRows(t.changed), rows / 2) << "of " << rows;
      if (step == 5 || step == 10) {
        EXPECT_EQ(raisedRows(t.changed), 0);
      }
    }
    SlabPasses update(*tasks);
    appendBuildPoissonMultigrid(t.fine, scene.grid.sides, settings, &t.mg, &update, &t.changed);
    update.runAll();
    // Consumed: the next update starts from no raised row on any level.
    EXPECT_FALSE(t.changed.any());
    for (const ChangedRows& level : t.mg.changed) EXPECT_FALSE(level.any());
    expectSameAsRebuilt(*tasks, scene, settings, t);
  }
}

// An update stopped after any slice, then run again on the same input, ends as a rebuild:
// whatever the stopped one changed and raised carries over. The input moves the sphere and
// the air's level set (coarse surface terms that change where no fine row did).
TEST_P(FluidMultigridUpdate, AnUpdateStoppedAfterAnySliceIsCompletedByTheNext) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  MovingScene scene(GetParam());
  MultigridSettings settings;
  Tracked before;
  scene.setTime(0.0, 0.0);
  SlabPasses first(*tasks);
  appendUpdate(scene, settings, &before, &first);
  first.runAll();
  scene.setTime(1.0, 0.0, 0.5);
  constexpr int64_t kSamples = 5000;
  int stops = 0;
  for (int slices = 1;; ++slices) {
    Tracked t = before;
    SlabPasses stopped(*tasks);
    appendUpdate(scene, settings, &t, &stopped);
    bool done = false;
    for (int s = 0; s < slices && !done; ++s) done = stopped.runSlice(kSamples);
    if (done) break;
    ++stops;
    SlabPasses again(*tasks);
    appendUpdate(scene, settings, &t, &again);
    again.runAll();
    SCOPED_TRACE(testing::Message() << "stopped after " << slices << " slices");
    expectSameAsRebuilt(*tasks, scene, settings, t);
    if (HasFailure()) break;
  }
  EXPECT_GT(stops, 20);
}

INSTANTIATE_TEST_SUITE_P(SmokeAndLiquid, FluidMultigridUpdate, testing::Values(false, true),
                         [](const testing::TestParamInfo<bool>& param) { return param.param ? "Liquid" : "Smoke"; });

}  // namespace
}  // namespace vp
