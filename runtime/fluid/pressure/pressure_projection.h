// Pressure projection of a MAC velocity field on a cut-cell grid: makes the velocity
// discretely divergence-free through the open parts of faces, with colliders' normal
// velocities on the covered parts.
//
//   1. b_c = -(rho h / dt) * netOutflow_c(u*)          (cut_cell_poisson.h for L and scaling)
//   2. L p = b by preconditioned filtered CG (PressureSolver picks the preconditioner),
//      warm-started from the last pressure, stopping at the tolerance, maxIterations or the
//      deadline (best iterate kept)
//   3. open faces (A_f > 0):  u_f -= dt / (rho h) * (p_high - p_low)   (p = 0 outside Open sides)
//      closed faces (A_f = 0, or below kMinOpenFraction): u_f = solid normal velocity
//      Wall faces:             u_f = 0
// Liquids (liquidPhi != nullptr, free_surface.h): only liquid cells are solved for; a face
// between a liquid and an air cell uses the ghost pressure p_c (1 - 1/theta) on the air side
// (the gradient the operator balanced), and faces with air on both sides (or an Open-side
// face of an air cell) keep their velocity: velocity extrapolation sets those.
// After a converged solve, |netOutflow_c| <= tolerance * |netOutflow(u*)|_2 on every cell,
// since netOutflow(u) = (dt / (rho h)) * (L p - b) cell by cell.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/allocator.h"
#include "core/budget_clock.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/pressure/mic0_preconditioner.h"
#include "fluid/pressure/poisson_multigrid.h"
#include "fluid/solids/face_fraction_field.h"
#include "linalg/conjugate_gradient.h"

namespace vp {

// The CG's preconditioner. All three solve the same system to the same tolerance. Cut-cell
// MGPCG is the default: at 128^3 (tests/bench/pressure_solve_bench.cpp, smoke past a sphere) it
// needs 7 iterations where voxel MGPCG needs 19 and MIC(0)-PCG 157, and it is the fastest of
// the three in time from 64^3 up.
enum class PressureSolver {
  Mic0Pcg,       // MIC(0), serial triangular solves (mic0_preconditioner.h)
  VoxelMgpcg,    // multigrid V-cycle, voxel-label coarse levels (McAdams et al. 2010), baseline
  CutCellMgpcg,  // multigrid V-cycle, cut-cell coarse levels (poisson_multigrid.h)
};

struct PressureSolveSettings {
  double tolerance = 1e-6;  // on |b - L p|_2 / |b|_2 (filtered)
  int maxIterations = 500;
  PressureSolver solver = PressureSolver::CutCellMgpcg;
  MultigridSettings multigrid{};  // smoother and cycle shape; its coarsening follows `solver`
  int minIterations = 0;  // run even past the deadline (the fluid actor asks for some)
  // The caller vouches that the fractions, the domain sides and the liquid (if any) are those
  // of the last projection with this state: the operator and its preconditioner are kept
  // instead of rebuilt (smoke among static colliders: the multigrid setup costs about a fifth
  // of a solve at 128^3). Ignored when the state holds no operator for this solver.
  bool operatorUnchanged = false;
};

struct PressureSolveStats {
  int iterations = 0;
  double relativeResidual = 0.0;
  bool converged = false;
  bool budgetCut = false;
  int64_t fluidCells = 0;
};

// What persists between steps: the pressure (warm start; physical units, so valid across dt
// changes) and the solver's cell-sized buffers, so a projection every frame does not
// reallocate them.
struct PressureState {
  Array<double> pressure;  // per cell; reset to 0 when the grid's cell count changes
  CutCellPoisson poisson;
  // Rows of poisson changed since the multigrid was last brought up to date: the multigrid
  // is updated where they reach instead of rebuilt (poisson_multigrid.h).
  ChangedRows poissonChanged;
  Mic0Preconditioner preconditioner;
  PoissonMultigrid multigrid;
  CgWorkspace cg;
  Array<double> rhs;
  bool operatorBuilt = false;  // poisson and the preconditioner below are those of builtFor
  PressureSolver builtFor = PressureSolver::CutCellMgpcg;
};

Status projectVelocity(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions, double dt,
                       double density, const Deadline& deadline, const PressureSolveSettings& settings,
                       PressureState& warmStart, PressureSolveStats* stats,
                       const double* liquidPhi = nullptr);

// The same projection in slices, for a fluid step spread over several frames:
//   prepare()                             checks and records the arguments, no heavy work
//   advanceSetup() until it returns true  operator, preconditioner, right-hand side, CG start
//   iterate() until it returns true       one CG iteration per call (solved() says whether done)
//   advanceFinish() until it returns true the velocity update; then stats()
// begin() and finish() are the setup and the finish in one call each (projectVelocity uses
// them), running the same passes. The deadline is the caller's: the solve stops only at the
// tolerance or maxIterations, and no pass's results depend on where slices are cut (nor on
// the worker count), so the projection is bitwise the same however it is sliced.
//
// A setup or finish slice runs passes (core/slab_passes.h) up to samplesPerSlice
// samples, and at least one unit of a pass. Samples are cells or faces, except that a coarse
// cell whose pass reads its children counts their 8. The passes, in order, and their units:
//   unless the operator is kept (operatorUnchanged):
//     operator (cut_cell_poisson.h)  couplings: face rows per axis; diagonal: cells;
//                                    region labels: cells, in two scans in cell order;
//                                    row spans: rows
//     Mic0Pcg: MIC(0) factorization  ONE unit of all cells (a serial dependency chain through
//                                    the grid, and only the baseline)
//     multigrid (poisson_multigrid.h), per coarse level: its coarsening (faces per axis, free
//                                    surface, Dirichlet parts, diagonal, regions, row spans)
//                                    and prolongation scales: rows; then per level its single-
//                                    precision copy: values (rows in an update); its boundary
//                                    cells: rows
//   right-hand side and the pressure cleared off fluid: cells
//   CG start                         ONE unit of all cells: the first residual, a
//                                    preconditioner application and the norms, like an
//                                    iteration (its global sums stay whole)
// Finish: the velocity update: face rows per axis.
// Everything passed to prepare must outlive the run and stay untouched until the finish's
// last slice; the run must not move in between.
class PressureProjectionRun {
 public:
  // samplesPerSlice >= 1 bounds the setup and finish slices.
  Status prepare(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions, double dt, double density,
                 const PressureSolveSettings& settings, PressureState& state, const double* liquidPhi,
                 int64_t samplesPerSlice);
  // One setup slice; true when the setup is done (the CG has started). `stop` as in
  // SlabPasses::runSlice.
  bool advanceSetup(const Deadline* stop = nullptr);
  // One CG iteration; true when the solve has ended.
  bool iterate() { return cg_->iterate(); }
  bool solved() const { return cg_ != nullptr && cg_->finished(); }
  // One finish slice (after the solve); true when the velocity is updated.
  bool advanceFinish(const Deadline* stop = nullptr);
  // After the finish (budgetCut is the caller's, false here).
  PressureSolveStats stats() const;
  // Of the last setup or finish slice: its samples, and the units of passes it ran. A slice
  // exceeds samplesPerSlice only when it is one unit.
  int64_t lastSliceSamples() const { return passes_.lastSliceSamples(); }
  int64_t lastSliceUnits() const { return passes_.lastSliceUnits(); }

  // prepare without a bound, then the whole setup.
  Status begin(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions, double dt, double density,
               const PressureSolveSettings& settings, PressureState& state, const double* liquidPhi = nullptr);
  // The whole finish; stats may be null.
  void finish(PressureSolveStats* stats);

 private:
  void appendSetup(const PressureSolveSettings& settings, bool keepOperator);
  void updateVelocityRows(int axis, int64_t begin, int64_t end);

  TaskSystem* tasks_ = nullptr;
  MacGrid* grid_ = nullptr;
  const FaceFractionField* fractions_ = nullptr;
  PressureState* state_ = nullptr;
  const double* liquidPhi_ = nullptr;
  double dt_ = 0.0, density_ = 0.0;
  int64_t samplesPerSlice_ = 0;
  bool finishing_ = false;  // passes_ holds the finish
  SlabPasses passes_;
  LinearSystem system_;
  std::unique_ptr<ConjugateGradientRun> cg_;
};

}  // namespace vp
