// The pressure projection in slices (PressureProjectionRun: prepare, advanceSetup, iterate,
// advanceFinish): bitwise projectVelocity's results however the setup and the finish are cut
// and on any worker count, for the three solvers, smoke and liquid, with the operator rebuilt
// or kept; slices bounded by samplesPerSlice; region labels equal to a flood fill's.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <deque>
#include <limits>
#include <random>

#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/pressure/pressure_projection.h"
#include "fluid_pressure_scenes.h"

namespace vp {
namespace {

using testscene::PressureScene;
using testscene::PressureSceneKind;

constexpr int64_t kWhole = std::numeric_limits<int64_t>::max();

// makePressureScene's colliders and velocity on an nx x ny x nz grid of the unit cube's
// spacing in x: a sphere, the top open; with `liquid`, liquid below 0.61 of the height.
void makeBoxScene(TaskSystem& tasks, int nx, int ny, int nz, bool liquid, PressureScene* scene) {
  MacGridSpec spec;
  spec.h = 1.0 / nx;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  const std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                        DomainSide::Open, DomainSide::Wall, DomainSide::Wall};
  ASSERT_EQ(initMacGrid(spec, sides, &scene->grid), Status::Ok) << lastError();
  ASSERT_EQ(initFaceFractionField(spec, &scene->fractions), Status::Ok) << lastError();
  const Eigen::Vector3d size(nx * spec.h, ny * spec.h, nz * spec.h);
  scene->colliders.assign(1, PreparedCollider{});
  ASSERT_EQ(prepareCollider(testscene::sphere(Eigen::Vector3d(0.5 * size.x(), 0.45 * size.y(), 0.5 * size.z()),
                                              0.2 * size.y()),
                            &scene->colliders[0]),
            Status::Ok);
  const PreparedCollider* list[] = {&scene->colliders[0]};
  ASSERT_EQ(computeFaceFractions(list, 1, &scene->fractions), Status::Ok) << lastError();
  testscene::fillSwirl(scene->grid);
  scene->liquidPhi.clear();
  if (!liquid) return;
  scene->liquidPhi.resize(static_cast<size_t>(scene->grid.cellCount()));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        scene->liquidPhi[scene->grid.cellIndex(i, j, k)] = scene->grid.cellCentre(i, j, k).y() - 0.61 * size.y();
}

struct SceneCase {
  const char* name;
  int nx, ny, nz;
  bool liquid;
  bool closed;  // a closed box (a floating region): from makePressureScene's ClosedTank
};

void makeCase(TaskSystem& tasks, const SceneCase& c, PressureScene* scene) {
  if (c.closed) {
    ASSERT_EQ(testscene::makePressureScene(tasks, PressureSceneKind::ClosedTank, c.nx, scene), Status::Ok);
    return;
  }
  makeBoxScene(tasks, c.nx, c.ny, c.nz, c.liquid, scene);
}

const SceneCase kCases[] = {
    {"smoke", 17, 12, 14, false, false},
    {"liquid", 16, 16, 16, true, false},
    {"closed", 12, 12, 12, false, true},
};

const PressureSolver kSolvers[] = {PressureSolver::Mic0Pcg, PressureSolver::VoxelMgpcg, PressureSolver::CutCellMgpcg};

const char* solverName(PressureSolver s) {
  return s == PressureSolver::Mic0Pcg ? "mic0" : s == PressureSolver::VoxelMgpcg ? "voxel" : "cutcell";
}

PressureSolveSettings settingsFor(PressureSolver solver, bool operatorUnchanged) {
  PressureSolveSettings s;
  s.tolerance = 1e-8;
  s.maxIterations = 1000;
  s.solver = solver;
  s.operatorUnchanged = operatorUnchanged;
  return s;
}

struct SliceCounts {
  int setup = 0, finish = 0;
  int64_t largestSetup = 0, largestFinish = 0;
};

// One projection through the slices; every slice is checked against the bound
// max(samplesPerSlice, largestUnit).
PressureSolveStats projectInSlices(TaskSystem& tasks, PressureScene& scene, const PressureSolveSettings& settings,
                                   PressureState& state, int64_t samplesPerSlice, int64_t largestUnit,
                                   SliceCounts* counts = nullptr) {
  SliceCounts local;
  SliceCounts& n = counts != nullptr ? *counts : local;
  const double* phi = scene.liquidPhi.empty() ? nullptr : scene.liquidPhi.data();
  PressureProjectionRun run;
  EXPECT_EQ(run.prepare(tasks, scene.grid, scene.fractions, 0.01, 1000.0, settings, state, phi, samplesPerSlice),
            Status::Ok)
      << lastError();
  const int64_t bound = std::max(samplesPerSlice, largestUnit);
  for (bool done = false; !done;) {
    done = run.advanceSetup();
    ++n.setup;
    n.largestSetup = std::max(n.largestSetup, run.lastSliceSamples());
    EXPECT_TRUE(run.lastSliceSamples() <= samplesPerSlice || run.lastSliceUnits() == 1)
        << "setup slice " << n.setup << ": " << run.lastSliceSamples() << " samples in " << run.lastSliceUnits()
        << " units";
    EXPECT_LE(run.lastSliceSamples(), bound) << "setup slice " << n.setup;
  }
  while (!run.iterate()) {
  }
  EXPECT_TRUE(run.solved());
  for (bool done = false; !done;) {
    done = run.advanceFinish();
    ++n.finish;
    n.largestFinish = std::max(n.largestFinish, run.lastSliceSamples());
    EXPECT_LE(run.lastSliceSamples(), bound) << "finish slice " << n.finish;
  }
  return run.stats();
}

void expectSameStats(const PressureSolveStats& a, const PressureSolveStats& b) {
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.relativeResidual, b.relativeResidual);
  EXPECT_EQ(a.converged, b.converged);
  EXPECT_EQ(a.fluidCells, b.fluidCells);
}

void expectSameOperator(const CutCellPoisson& a, const CutCellPoisson& b) {
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(a.coupling[axis], b.coupling[axis]);
    EXPECT_EQ(a.openFraction[axis], b.openFraction[axis]);
  }
  EXPECT_EQ(a.diagonal, b.diagonal);
  EXPECT_EQ(a.rowSpan, b.rowSpan);
  EXPECT_EQ(a.region, b.region);
  EXPECT_EQ(a.regionFloating, b.regionFloating);
  EXPECT_EQ(a.regionCellCount, b.regionCellCount);
  EXPECT_EQ(a.fluidCellCount, b.fluidCellCount);
  EXPECT_EQ(a.air, b.air);
  EXPECT_EQ(a.liquidPhi, b.liquidPhi);
  EXPECT_EQ(a.surfaceDirichlet, b.surfaceDirichlet);
}

void expectSameBoundaryCells(const BoundaryCellLists& a, const BoundaryCellLists& b) {
  for (size_t colour = 0; colour < 2; ++colour) {
    ASSERT_EQ(a.byColour[colour].size(), b.byColour[colour].size());
    for (size_t e = 0; e < a.byColour[colour].size(); ++e)
      EXPECT_EQ(std::memcmp(&a.byColour[colour][e], &b.byColour[colour][e], sizeof(BoundaryCell)), 0) << "entry " << e;
  }
  EXPECT_EQ(a.reads, b.reads);
}

void expectSameSolverState(const PressureState& a, const PressureState& b, PressureSolver solver) {
  expectSameOperator(a.poisson, b.poisson);
  if (solver == PressureSolver::Mic0Pcg) {
    EXPECT_EQ(a.preconditioner.inverseSqrtPivot, b.preconditioner.inverseSqrtPivot);
    return;
  }
  const PoissonMultigrid& x = a.multigrid;
  const PoissonMultigrid& y = b.multigrid;
  ASSERT_EQ(x.levelCount(), y.levelCount());
  for (size_t l = 0; l < x.coarse.size(); ++l) expectSameOperator(x.coarse[l], y.coarse[l]);
  for (size_t l = 0; l < x.single.size(); ++l) {
    for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(x.single[l].coupling[axis], y.single[l].coupling[axis]);
    EXPECT_EQ(x.single[l].diagonal, y.single[l].diagonal);
    EXPECT_EQ(x.single[l].rowSpan, y.single[l].rowSpan);
    expectSameBoundaryCells(x.boundaryCells[l], y.boundaryCells[l]);
  }
  EXPECT_EQ(x.prolongScale, y.prolongScale);
  EXPECT_EQ(x.coarseFloating, y.coarseFloating);
}

// The largest unit a setup pass may run as one slice below the whole ones (MIC(0), the CG
// start, one cell count each): a fine face row, or a coarse face row reading 8 children.
int64_t largestRow(const PressureScene& scene) {
  const MacGridSpec& g = scene.grid.spec;
  return std::max<int64_t>(g.nx + 1, 8 * ((g.nx + 1) / 2 + 1));
}

// The projections of a step sequence: one, or (operatorUnchanged) a first that builds and a
// second, after the velocity changed, that keeps the operator.
template <class Project>
void runProjections(PressureScene& scene, bool keep, const Project& project) {
  project(false);
  if (!keep) return;
  for (double& u : scene.grid.velocity[1]) u += 0.3;
  project(true);
}

TEST(FluidPressureSlices, SlicedSetupAndFinishAreBitwiseProjectVelocity) {
  auto reference = TaskSystem::create(TaskHooks{}, 2);
  const int workerCounts[] = {1, 3};
  const int64_t sampleCounts[] = {1, 37, 500, kWhole};
  for (const SceneCase& sc : kCases)
    for (PressureSolver solver : kSolvers)
      for (bool keep : {false, true}) {
        SCOPED_TRACE(std::string(sc.name) + " " + solverName(solver) + (keep ? " kept" : " rebuilt"));
        PressureScene whole;
        makeCase(*reference, sc, &whole);
        PressureState wholeState;
        PressureSolveStats wholeStats;
        runProjections(whole, keep, [&](bool unchanged) {
          const double* phi = whole.liquidPhi.empty() ? nullptr : whole.liquidPhi.data();
          ASSERT_EQ(projectVelocity(*reference, whole.grid, whole.fractions, 0.01, 1000.0, Deadline(),
                                    settingsFor(solver, unchanged), wholeState, &wholeStats, phi),
                    Status::Ok)
              << lastError();
        });
        EXPECT_TRUE(wholeStats.converged);
        for (int workers : workerCounts)
          for (int64_t samples : sampleCounts) {
            SCOPED_TRACE(std::to_string(workers) + " workers, " + std::to_string(samples) + " samples per slice");
            auto tasks = TaskSystem::create(TaskHooks{}, workers);
            PressureScene sliced;
            makeCase(*tasks, sc, &sliced);
            PressureState state;
            PressureSolveStats stats;
            runProjections(sliced, keep, [&](bool unchanged) {
              stats = projectInSlices(*tasks, sliced, settingsFor(solver, unchanged), state, samples,
                                      std::max(largestRow(sliced), sliced.grid.cellCount()));
            });
            expectSameStats(stats, wholeStats);
            EXPECT_EQ(state.pressure, wholeState.pressure);
            for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(sliced.grid.velocity[axis], whole.grid.velocity[axis]);
            expectSameSolverState(state, wholeState, solver);
          }
      }
}

TEST(FluidPressureSlices, SmallSlicesSplitEveryPassButTheWholeOnes) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  for (PressureSolver solver : kSolvers)
    for (bool liquid : {false, true}) {
      SCOPED_TRACE(std::string(solverName(solver)) + (liquid ? " liquid" : " smoke"));
      PressureScene scene;
      makeBoxScene(*tasks, 24, 15, 24, liquid, &scene);
      PressureState state;
      SliceCounts counts;
      const int64_t samples = 64;
      // Bounded by a row wherever a pass is split: only MIC(0) and the CG start may exceed it.
      const int64_t row = largestRow(scene);
      PressureProjectionRun run;
      const double* phi = liquid ? scene.liquidPhi.data() : nullptr;
      ASSERT_EQ(run.prepare(*tasks, scene.grid, scene.fractions, 0.01, 1000.0, settingsFor(solver, false), state,
                            phi, samples),
                Status::Ok);
      int overRow = 0;
      for (bool done = false; !done;) {
        done = run.advanceSetup();
        ++counts.setup;
        if (run.lastSliceSamples() > std::max(samples, row)) {
          ++overRow;
          EXPECT_EQ(run.lastSliceUnits(), 1);
          EXPECT_EQ(run.lastSliceSamples(), scene.grid.cellCount());
        }
      }
      EXPECT_EQ(overRow, solver == PressureSolver::Mic0Pcg ? 2 : 1);
      const int64_t cells = scene.grid.cellCount();
      // Every cell is visited by several passes; far more slices than levels.
      EXPECT_GT(counts.setup, 4 * cells / samples);
      if (solver != PressureSolver::Mic0Pcg) {
        EXPECT_GT(counts.setup, state.multigrid.levelCount());
      }
      while (!run.iterate()) {
      }
      for (bool done = false; !done;) {
        done = run.advanceFinish();
        ++counts.finish;
        EXPECT_LE(run.lastSliceSamples(), std::max<int64_t>(samples, scene.grid.spec.nx + 1));
      }
      EXPECT_GE(counts.finish, 3 * cells / samples);
      std::printf("    %-7s %-6s 24x15x24 at %lld samples: %d setup slices, %d finish slices\n", solverName(solver),
                  liquid ? "liquid" : "smoke", static_cast<long long>(samples), counts.setup, counts.finish);
    }
}

TEST(FluidPressureSlices, AnUnboundedSliceIsTheWholeSetupOrFinish) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  PressureScene scene;
  makeBoxScene(*tasks, 24, 15, 24, true, &scene);
  PressureState state;
  SliceCounts whole;
  projectInSlices(*tasks, scene, settingsFor(PressureSolver::CutCellMgpcg, false), state, kWhole, kWhole, &whole);
  EXPECT_EQ(whole.setup, 1);
  EXPECT_EQ(whole.finish, 1);
  // The default scene's size: the counts a frame plan sees.
  for (int64_t samples : {16384, 4096}) {
    makeBoxScene(*tasks, 24, 15, 24, true, &scene);
    SliceCounts counts;
    projectInSlices(*tasks, scene, settingsFor(PressureSolver::CutCellMgpcg, false), state, samples,
                    scene.grid.cellCount(), &counts);
    std::printf("    cut-cell MGPCG, liquid 24x15x24 at %lld samples: %d setup slices (largest %lld samples), "
                "%d finish slices (largest %lld)\n",
                static_cast<long long>(samples), counts.setup, static_cast<long long>(counts.largestSetup),
                counts.finish, static_cast<long long>(counts.largestFinish));
    EXPECT_GT(counts.setup, 1);
  }
}

TEST(FluidPressureSlices, RejectsABadSliceBound) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  PressureScene scene;
  makeBoxScene(*tasks, 8, 8, 8, false, &scene);
  PressureState state;
  PressureProjectionRun run;
  EXPECT_EQ(run.prepare(*tasks, scene.grid, scene.fractions, 0.01, 1000.0, PressureSolveSettings{}, state, nullptr, 0),
            Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("samplesPerSlice"), std::string::npos);
}

// The flood fill labelFluidRegions replaced: seeds in cell order, breadth first through
// positive couplings.
void floodFillRegions(const CutCellPoisson& op, Array<int32_t>* region, Array<uint8_t>* floating,
                      Array<int64_t>* counts) {
  const MacGridSpec& g = op.grid;
  const int64_t nx = g.nx, ny = g.ny, nz = g.nz, cells = nx * ny * nz;
  region->assign(static_cast<size_t>(cells), -1);
  floating->clear();
  counts->clear();
  for (int64_t seed = 0; seed < cells; ++seed) {
    if ((*region)[static_cast<size_t>(seed)] >= 0 || !(op.diagonal[static_cast<size_t>(seed)] > 0.0)) continue;
    const int32_t id = static_cast<int32_t>(floating->size());
    bool isFloating = true;
    std::deque<int64_t> queue{seed};
    (*region)[static_cast<size_t>(seed)] = id;
    int64_t count = 0;
    while (!queue.empty()) {
      const int64_t c = queue.front();
      queue.pop_front();
      ++count;
      if (dirichletPart(op, c) > 0.0) isFloating = false;
      const int64_t i = c % nx, j = (c / nx) % ny, k = c / (nx * ny);
      const int64_t fu = i + (nx + 1) * (j + ny * k), fv = i + nx * (j + (ny + 1) * k);
      const struct {
        int axis;
        int64_t face, nb;
      } faces[6] = {{0, fu, i > 0 ? c - 1 : -1},           {0, fu + 1, i + 1 < nx ? c + 1 : -1},
                    {1, fv, j > 0 ? c - nx : -1},          {1, fv + nx, j + 1 < ny ? c + nx : -1},
                    {2, c, k > 0 ? c - nx * ny : -1},      {2, c + nx * ny, k + 1 < nz ? c + nx * ny : -1}};
      for (const auto& f : faces) {
        if (f.nb < 0 || !(op.coupling[f.axis][static_cast<size_t>(f.face)] > 0.0)) continue;
        if ((*region)[static_cast<size_t>(f.nb)] < 0) {
          (*region)[static_cast<size_t>(f.nb)] = id;
          queue.push_back(f.nb);
        }
      }
    }
    floating->push_back(isFloating ? 1 : 0);
    counts->push_back(count);
  }
}

TEST(FluidPressureSlices, RegionLabelsAreThoseOfAFloodFillHoweverTheScanIsCut) {
  // Random couplings with many closed faces cut the grid into many regions, some with a
  // Dirichlet part, some floating, some single cells.
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    CutCellPoisson op;
    op.grid.nx = 5 + trial % 4;
    op.grid.ny = 4 + trial % 3;
    op.grid.nz = 3 + trial % 5;
    op.grid.h = 0.1;
    const int64_t nx = op.grid.nx, ny = op.grid.ny, nz = op.grid.nz, cells = nx * ny * nz;
    const double closedShare = 0.6 + 0.01 * trial;
    const int64_t faces[3] = {(nx + 1) * ny * nz, nx * (ny + 1) * nz, nx * ny * (nz + 1)};
    for (int a = 0; a < 3; ++a) {
      op.coupling[a].assign(static_cast<size_t>(faces[a]), 0.0);
      for (int64_t k = 0; k < nz; ++k)
        for (int64_t j = 0; j < ny; ++j)
          for (int64_t i = 0; i < nx; ++i) {
            const int64_t at[3] = {i, j, k};
            if (at[a] == 0) continue;  // interior faces only: the low face of cells 1 ..
            const int64_t f = a == 0 ? i + (nx + 1) * (j + ny * k) : a == 1 ? i + nx * (j + (ny + 1) * k)
                                                                          : i + nx * (j + ny * k);
            op.coupling[a][static_cast<size_t>(f)] = unit(rng) < closedShare ? 0.0 : 0.25 + unit(rng);
          }
    }
    op.diagonal.assign(static_cast<size_t>(cells), 0.0);
    for (int64_t c = 0; c < cells; ++c) {
      const int64_t i = c % nx, j = (c / nx) % ny, k = c / (nx * ny);
      double sum = op.coupling[0][static_cast<size_t>(i + (nx + 1) * (j + ny * k))] +
                   op.coupling[0][static_cast<size_t>(i + 1 + (nx + 1) * (j + ny * k))] +
                   op.coupling[1][static_cast<size_t>(i + nx * (j + (ny + 1) * k))] +
                   op.coupling[1][static_cast<size_t>(i + nx * (j + 1 + (ny + 1) * k))] +
                   op.coupling[2][static_cast<size_t>(c)] + op.coupling[2][static_cast<size_t>(c + nx * ny)];
      if (unit(rng) < 0.05) sum += 1.0;  // a Dirichlet face
      op.diagonal[static_cast<size_t>(c)] = sum;
    }
    Array<int32_t> region;
    Array<uint8_t> floating;
    Array<int64_t> counts;
    floodFillRegions(op, &region, &floating, &counts);
    for (int64_t samples : {int64_t{1}, int64_t{7}, kWhole}) {
      CutCellPoisson labelled = op;
      SlabPasses passes(*tasks);
      appendLabelFluidRegions(&labelled, &passes);
      while (!passes.runSlice(samples)) {
      }
      EXPECT_EQ(labelled.region, region) << "trial " << trial;
      EXPECT_EQ(labelled.regionFloating, floating) << "trial " << trial;
      EXPECT_EQ(labelled.regionCellCount, counts) << "trial " << trial;
      int64_t fluid = 0;
      for (int64_t n : counts) fluid += n;
      EXPECT_EQ(labelled.fluidCellCount, fluid);
    }
    EXPECT_GT(counts.size(), 1u) << "trial " << trial << ": a single region";
  }
}

}  // namespace
}  // namespace vp
