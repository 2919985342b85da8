// Cut-cell pressure projection (see pressure_projection.h).
#include "fluid/pressure_projection.h"

#include <cmath>

#include "core/parallel_for.h"
#include "fluid/free_surface.h"

namespace vp {

Status PressureProjectionRun::begin(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions, double dt,
                                    double density, const PressureSolveSettings& settings, PressureState& state,
                                    const double* liquidPhi) {
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
  tasks_ = &tasks;
  grid_ = &grid;
  fractions_ = &fractions;
  state_ = &state;
  liquidPhi_ = liquidPhi;
  dt_ = dt;
  density_ = density;
  const bool reuse = settings.operatorUnchanged && state.operatorBuilt && state.builtFor == settings.solver &&
                     state.poisson.diagonal.size() == static_cast<size_t>(grid.cellCount());
  if (!reuse) {
    state.operatorBuilt = false;
    VP_TRY(buildCutCellPoisson(tasks, grid, fractions, &state.poisson, liquidPhi));
    if (settings.solver == PressureSolver::Mic0Pcg) {
      VP_TRY(buildMic0Preconditioner(state.poisson, Mic0Settings{}, &state.preconditioner));
    } else {
      MultigridSettings mg = settings.multigrid;
      mg.coarsening = settings.solver == PressureSolver::VoxelMgpcg ? MultigridCoarsening::Voxel
                                                                     : MultigridCoarsening::CutCell;
      VP_TRY(buildPoissonMultigrid(tasks, state.poisson, grid.sides, mg, &state.multigrid));
    }
    state.operatorBuilt = true;
    state.builtFor = settings.solver;
  }
  const CutCellPoisson& op = state.poisson;
  const int64_t cells = grid.cellCount();

  state.rhs.resize(static_cast<size_t>(cells));
  computeNetOutflow(tasks, grid, fractions, op, state.rhs.data());
  const double rhsScale = -density * grid.spec.h / dt;
  for (double& b : state.rhs) b *= rhsScale;

  if (state.pressure.size() != static_cast<size_t>(cells)) state.pressure.assign(static_cast<size_t>(cells), 0.0);
  // Cells that left the fluid keep no stale pressure (they would leak into open faces' gradients).
  for (int64_t c = 0; c < cells; ++c)
    if (!op.isFluid(static_cast<size_t>(c))) state.pressure[static_cast<size_t>(c)] = 0.0;

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
  cg_ = std::make_unique<ConjugateGradientRun>(tasks, system_, state.rhs.data(), state.pressure.data(), cgSettings,
                                               state.cg);
  cg_->start();
  return Status::Ok;
}

void PressureProjectionRun::finish(PressureSolveStats* stats) {
  TaskSystem& tasks = *tasks_;
  MacGrid& grid = *grid_;
  const FaceFractionField& fractions = *fractions_;
  const MacGridSpec& g = grid.spec;
  const double h = g.h, dt = dt_, density = density_;
  const double* liquidPhi = liquidPhi_;
  PressureState& state = *state_;
  // Velocity update, face by face (each face written once: parallel over face rows).
  const double gradientScale = dt / (density * h);
  const double* p = state.pressure.data();
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid.faceDims(a);
    const int cellsAlong = a == 0 ? g.nx : a == 1 ? g.ny : g.nz;
    std::vector<double>& u = grid.velocity[a];
    parallelFor(tasks, static_cast<int64_t>(d.z()) * d.y(), 16, [&](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) {
        const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
        for (int i = 0; i < d.x(); ++i) {
          const size_t f = grid.faceIndex(a, i, j, k);
          if (grid.isWallFace(a, i, j, k)) {
            u[f] = 0.0;
            continue;
          }
          if (!(effectiveOpenFraction(grid, fractions, a, i, j, k) > 0.0)) {
            u[f] = fractions.solidVelocity[a][f];
            continue;
          }
          const int along = a == 0 ? i : a == 1 ? j : k;
          Eigen::Vector3i low(i, j, k);
          low[a] -= 1;
          const bool hasLow = along > 0, hasHigh = along < cellsAlong;
          const size_t cellLow = hasLow ? grid.cellIndex(low.x(), low.y(), low.z()) : 0;
          const size_t cellHigh = hasHigh ? grid.cellIndex(i, j, k) : 0;
          // Outside an Open side the ghost pressure is 0.
          double pLow = hasLow ? p[cellLow] : 0.0;
          double pHigh = hasHigh ? p[cellHigh] : 0.0;
          if (liquidPhi != nullptr) {
            const bool liquidLow = hasLow && isLiquid(liquidPhi[cellLow]);
            const bool liquidHigh = hasHigh && isLiquid(liquidPhi[cellHigh]);
            if (!liquidLow && !liquidHigh) continue;
            if (liquidLow && hasHigh && !liquidHigh)
              pHigh = pLow * (1.0 - 1.0 / freeSurfaceTheta(liquidPhi[cellLow], liquidPhi[cellHigh]));
            else if (liquidHigh && hasLow && !liquidLow)
              pLow = pHigh * (1.0 - 1.0 / freeSurfaceTheta(liquidPhi[cellHigh], liquidPhi[cellLow]));
          }
          u[f] -= gradientScale * (pHigh - pLow);
        }
      }
    });
  }

  if (stats != nullptr) {
    const CgResult& result = cg_->result();
    stats->iterations = result.iterations;
    stats->relativeResidual = result.relativeResidual;
    stats->converged = result.converged;
    stats->budgetCut = false;
    stats->fluidCells = state.poisson.fluidCellCount;
  }
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
