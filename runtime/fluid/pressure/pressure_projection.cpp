// Cut-cell pressure projection (see pressure_projection.h).
#include "fluid/pressure/pressure_projection.h"

#include <cmath>

#include "core/parallel_for.h"
#include "fluid/surface/free_surface.h"
#include "gpu_kernels/pressure_update_kernels.h"

namespace vp {

namespace {

constexpr int64_t kCellGrain = 4096;
constexpr int64_t kFaceRowGrain = 16;

}  // namespace

Status PressureProjectionRun::prepare(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions, double dt,
                                      double density, const PressureSolveSettings& settings, PressureState& state,
                                      const double* liquidPhi, int64_t samplesPerSlice) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    return fail(Status::InvalidArgument, "pressure projection: dt = %g must be positive and finite", dt);
  if (!(density > 0.0) || !std::isfinite(density))
    return fail(Status::InvalidArgument, "pressure projection: density = %g must be positive and finite",
                density);
  if (!(settings.tolerance > 0.0) || !std::isfinite(settings.tolerance))
    return fail(Status::InvalidArgument, "pressure projection: tolerance = %g must be positive and finite",
                settings.tolerance);
  if (settings.maxIterations < 0)
    return fail(Status::InvalidArgument, "pressure projection: maxIterations = %d must be >= 0",
                settings.maxIterations);
  if (samplesPerSlice < 1)
    return fail(Status::InvalidArgument, "pressure projection: samplesPerSlice = %lld must be >= 1",
                static_cast<long long>(samplesPerSlice));
  VP_TRY(checkCutCellPoissonInputs(grid, fractions));
  const bool keepOperator = settings.operatorUnchanged && state.operatorBuilt && state.builtFor == settings.solver &&
                            state.poisson.diagonal.size() == static_cast<size_t>(grid.cellCount());
  if (!keepOperator && settings.solver != PressureSolver::Mic0Pcg)
    VP_TRY(checkPoissonMultigrid(grid.spec, settings.multigrid));
  tasks_ = &tasks;
  grid_ = &grid;
  fractions_ = &fractions;
  state_ = &state;
  liquidPhi_ = liquidPhi;
  dt_ = dt;
  density_ = density;
  samplesPerSlice_ = samplesPerSlice;
  finishing_ = false;
  cg_.reset();
  // A setup stopped halfway leaves no operator that claims to be built.
  if (!keepOperator) state.operatorBuilt = false;
  passes_.reset(tasks);
  appendSetup(settings, keepOperator);
  return Status::Ok;
}

void PressureProjectionRun::appendSetup(const PressureSolveSettings& settings, bool keepOperator) {
  PressureState& state = *state_;
  const int64_t cells = grid_->cellCount();
  if (!keepOperator) {
    appendBuildCutCellPoisson(*grid_, *fractions_, &state.poisson, liquidPhi_, &passes_, &state.poissonChanged);
    if (settings.solver == PressureSolver::Mic0Pcg) {
      // Mic0Settings{} is valid, so the build cannot fail.
      passes_.addWhole(cells, [&state] {
        buildMic0Preconditioner(state.poisson, Mic0Settings{}, &state.preconditioner);
      });
    } else {
      MultigridSettings mg = settings.multigrid;
      mg.coarsening = settings.solver == PressureSolver::VoxelMgpcg ? MultigridCoarsening::Voxel
                                                                     : MultigridCoarsening::CutCell;
      appendBuildPoissonMultigrid(state.poisson, grid_->sides, mg, &state.multigrid, &passes_, &state.poissonChanged);
    }
    passes_.addStep([&state, solver = settings.solver] {
      state.operatorBuilt = true;
      state.builtFor = solver;
    });
  }

  passes_.addStep([&state, cells] {
    state.rhs.resize(static_cast<size_t>(cells));
    if (state.pressure.size() != static_cast<size_t>(cells)) state.pressure.assign(static_cast<size_t>(cells), 0.0);
  });
  const double rhsScale = -density_ * grid_->spec.h / dt_;
  passes_.addParallel(cells, 1, kCellGrain, [this, rhsScale](int64_t begin, int64_t end) {
    PressureState& st = *state_;
    computeNetOutflowCells(*grid_, *fractions_, st.poisson, begin, end, st.rhs.data());
    for (int64_t c = begin; c < end; ++c) {
      st.rhs[static_cast<size_t>(c)] *= rhsScale;
      // Cells that left the fluid keep no stale pressure (they would leak into open faces' gradients).
      if (!st.poisson.isFluid(static_cast<size_t>(c))) st.pressure[static_cast<size_t>(c)] = 0.0;
    }
  });

  system_ = LinearSystem{};
  system_.size = cells;
  system_.apply = [this](const double* x, double* y) { applyCutCellPoisson(*tasks_, state_->poisson, x, y); };
  if (settings.solver == PressureSolver::Mic0Pcg)
    system_.precondition = [this](const double* r, double* z) {
      applyMic0Preconditioner(state_->poisson, state_->preconditioner, r, z);
    };
  else
    system_.precondition = [this](const double* r, double* z) {
      applyPoissonMultigrid(*tasks_, state_->poisson, state_->multigrid, r, z);
    };
  system_.filter = [this](double* v) { filterCutCellPoisson(*tasks_, state_->poisson, v); };
  CgSettings cgSettings;
  cgSettings.relativeTolerance = settings.tolerance;
  cgSettings.maxIterations = settings.maxIterations;
  passes_.addWhole(cells, [this, cgSettings] {
    cg_ = std::make_unique<ConjugateGradientRun>(*tasks_, system_, state_->rhs.data(), state_->pressure.data(),
                                                 cgSettings, state_->cg);
    cg_->start();
  });
}

bool PressureProjectionRun::advanceSetup(const Deadline* stop) { return passes_.runSlice(samplesPerSlice_, stop); }

bool PressureProjectionRun::advanceFinish(const Deadline* stop) {
  if (!finishing_) {
    finishing_ = true;
    passes_.reset(*tasks_);
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3i d = grid_->faceDims(a);
      passes_.addParallel(static_cast<int64_t>(d.z()) * d.y(), d.x(), kFaceRowGrain,
                          [this, a](int64_t begin, int64_t end) { updateVelocityRows(a, begin, end); });
    }
  }
  return passes_.runSlice(samplesPerSlice_, stop);
}

// Face by face (gpu_kernels/pressure_update_kernels.h).
void PressureProjectionRun::updateVelocityRows(int a, int64_t begin, int64_t end) {
  const MacGrid& grid = *grid_;
  const kernels::PressureUpdateFields fields{fractions_->open[a].data(), fractions_->solidVelocity[a].data(),
                                             state_->pressure.data(), liquidPhi_, dt_ / (density_ * grid.spec.h)};
  const kernels::MacLayout layout = grid.layout();
  const Eigen::Vector3i d = grid.faceDims(a);
  double* u = grid_->velocity[a].data();
  for (int64_t row = begin; row < end; ++row)
    for (int i = 0; i < d.x(); ++i) kernels::pressureUpdateFaceAt(fields, layout, a, i, row % d.y(), row / d.y(), u);
}

PressureSolveStats PressureProjectionRun::stats() const {
  PressureSolveStats stats;
  const CgResult& result = cg_->result();
  stats.iterations = result.iterations;
  stats.relativeResidual = result.relativeResidual;
  stats.converged = result.converged;
  stats.budgetCut = false;
  stats.fluidCells = state_->poisson.fluidCellCount;
  return stats;
}

Status PressureProjectionRun::begin(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions, double dt,
                                    double density, const PressureSolveSettings& settings, PressureState& state,
                                    const double* liquidPhi) {
  VP_TRY(prepare(tasks, grid, fractions, dt, density, settings, state, liquidPhi, INT64_MAX));
  while (!advanceSetup()) {
  }
  return Status::Ok;
}

void PressureProjectionRun::finish(PressureSolveStats* stats) {
  while (!advanceFinish()) {
  }
  if (stats != nullptr) *stats = this->stats();
}

Status projectVelocity(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions, double dt,
                       double density, const Deadline& deadline, const PressureSolveSettings& settings,
                       PressureState& state, PressureSolveStats* stats, const double* liquidPhi) {
  PressureProjectionRun run;
  VP_TRY(run.begin(tasks, grid, fractions, dt, density, settings, state, liquidPhi));
  int iterations = 0;
  bool budgetCut = false;
  while (!run.solved()) {
    if (iterations >= settings.minIterations && deadline.expired()) {
      budgetCut = true;
      break;
    }
    run.iterate();
    ++iterations;
  }
  run.finish(stats);
  if (stats != nullptr) stats->budgetCut = budgetCut;
  return Status::Ok;
}

}  // namespace vp
