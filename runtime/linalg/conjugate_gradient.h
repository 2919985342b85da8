// Preconditioned conjugate gradients that respects the frame budget.
//
// The solve stops at the tolerance, at maxIterations, or when the deadline passes; it then
// keeps its last iterate, which is the best one it has: CG minimizes the A-norm of the error
// over a growing subspace, so each iterate is at least as good as the one before (the
// residual norm may wobble, the energy error does not). The caller warm-starts the next
// frame from it.
//
// Constraints use the filtered CG of Baraff & Witkin 1998: `filter` projects a vector onto
// the allowed subspace (zero on pinned degrees of freedom, tangential on contacts), applied
// to the residual and to every search direction, so constrained components of x keep
// whatever value the caller put there.
#pragma once

#include <cstdint>
#include <functional>

#include "core/allocator.h"
#include "core/budget_clock.h"
#include "core/task_system.h"

namespace vp {

struct CgSettings {
  double relativeTolerance = 1e-4;  // on |r| / |filtered b|
  int maxIterations = 200;
  // Iterations run even after the deadline (for solves that must make some progress every
  // frame, see PressureSolveSettings::minIterations); 0: the deadline is checked before each.
  int minIterations = 0;
};

struct CgResult {
  int iterations = 0;
  double relativeResidual = 0.0;
  bool converged = false;
  bool budgetCut = false;
};

struct LinearSystem {
  int64_t size = 0;                                        // number of scalars
  std::function<void(const double* x, double* y)> apply;   // y = A x
  std::function<void(const double* r, double* z)> precondition;  // z = P^-1 r; empty: identity
  std::function<void(double* v)> filter;                   // in place; empty: none
};

// Scratch vectors live in the workspace so a solver reused every frame does not allocate.
struct CgWorkspace {
  Array<double> r, z, p, q;
};

CgResult solveConjugateGradient(TaskSystem& tasks, const LinearSystem& system, const double* b, double* x,
                                const CgSettings& settings, const Deadline& deadline, CgWorkspace& work);

// With an accuracy floor: past `deadline` the solve stops only once its relative residual is
// at or below floorTolerance, and at `floorDeadline` in any case (budgetCut says it stopped
// on time; the residual says whether it was above the floor).
CgResult solveConjugateGradient(TaskSystem& tasks, const LinearSystem& system, const double* b, double* x,
                                const CgSettings& settings, const Deadline& deadline, CgWorkspace& work,
                                double floorTolerance, const Deadline& floorDeadline);

// The same solve, one iteration per call, for work that is spread over several frames: every
// quantity the next iteration needs lives here and in the workspace, so stopping between two
// calls and resuming later gives bitwise the iterates of an uninterrupted solve. The system,
// b, x and the workspace must outlive the run and stay untouched between calls. The deadline
// is the caller's business (minIterations is not read).
class ConjugateGradientRun {
 public:
  ConjugateGradientRun(TaskSystem& tasks, const LinearSystem& system, const double* b, double* x,
                       const CgSettings& settings, CgWorkspace& work);
  // Initial residual, first search direction; true when that already ends the solve.
  bool start();
  // One iteration; true when the solve has ended (converged, maxIterations or breakdown).
  bool iterate();
  bool finished() const { return finished_; }
  const CgResult& result() const { return result_; }

 private:
  void precondition(const double* r, double* z);
  void filter(double* v);

  TaskSystem& tasks_;
  const LinearSystem& system_;
  const double* b_;
  double* x_;
  CgSettings settings_;
  CgWorkspace& work_;
  CgResult result_;
  double bNorm_ = 0.0, rz_ = 0.0;
  bool finished_ = false;
};

}  // namespace vp
