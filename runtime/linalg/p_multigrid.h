// p-multigrid: a V-cycle over the polynomial degrees of one mesh (cubic -> quadratic ->
// linear), used as the CG preconditioner of the deformable solve for degree >= 2, or on its
// own as a stationary solver (linalg/richardson_iteration.h). The levels come from
// deform/degree_hierarchy.h: what this class needs of them is the per-node prolongations
// (BB degree elevation), so it knows nothing about elements.
//
// Coarse operators, two kinds (DeformableSolverSettings::pMultigridCoarseOperator picks; F
// below is the per-node 3x3 projector CG filters with: 0 pinned, I − nnᵀ sliding, else I):
//  - re-discretized (the default): the caller assembles each coarse level at its own degree
//    with the fine level's element rotations and integrator scalings
//    (deform/degree_level_assembly.h), and update() restricts it in place to the constrained
//    coarse space. Its stiffness is the Galerkin product Pᵀ K P exactly, for any rotations
//    (elevation is exact and commutes with a per-element rotation); its mass is the coarse
//    degree's lumped mass rather than the elevated fine one. An assembled operator cannot
//    truncate a coarse function at the constrained fine nodes it reaches, so a coarse node
//    may move only where every fine node reading it may: F_c projects onto the intersection
//    of their ranges (the null space of Σ (I − F_i)). A pinned face then pins the coarse
//    degree's own control points on it, P F_c maps into the constrained fine space, and the
//    constrained coarse operator is the Galerkin operator of that conforming coarse space
//    (tests/unit/linalg_p_multigrid_test.cpp checks it densely). With the union rule below
//    instead, the coarse nodes on a clamped face's edges stayed free in a coarse problem
//    that believes the face moves with them: 39 CG iterations instead of 16 on
//    BM_DeformSolve, and the cycle alone did not converge.
//  - Galerkin: A_c = P̃ᵀ A P̃ with the constrained prolongation P̃ = F_f P F_c, F_c the
//    projector onto the directions some fine reader may move in (the range of Σ F_i: I where
//    any reader is free, 0 where all are pinned). The product truncates coarse functions at
//    constrained fine nodes: a larger coarse space, the best correction in the energy norm
//    over it, at the price of one sparse triple product per level and update.
// Measured on the 2-core machine, the two in the same runs (random interleaving, load
// 0.5-1.5), medians; the rest of the setup (smoother diagonals, λmax, coarsest multigrid) is
// common to both:
//                                     Galerkin                 re-discretized
//   BM_DeformSolve/pmg_pcg/cubic      16 it, setup 90 ms,      16 it, setup 58 ms,
//     (pinned face, PCG to 1e-6)      446 ms in all            381 ms in all
//   BM_DeformSolve/pmg/cubic          42 cycles, 1031 ms       42 cycles, 969 ms
//   BM_DeformContact (cubic cube      11.66 it/step, setup     12.18 it/step, setup
//     tumbling onto a plane)          13.6 ms/step, 10.5 s CPU  5.0 ms/step, 7.8 s CPU
//   BM_DeformQuadraticBeam/13000      8.47 it/step, setup      8.58 it/step, setup
//     (quadratic, 2 -> 1, pinned)     16.8 ms/step, 10.2 Hz    10.2 ms/step, 10.4 Hz
// (BM_DeformContact and BM_DeformQuadraticBeam: the step's assemble phase, mostly this
// setup. On a quiet machine, load 0.3: BM_DeformSolve setup 64 against 44 ms.) The
// conforming coarse space costs 0-4% more iterations; the cheaper setup more than pays for
// it, most where contacts change the constraint set within a step, since every active-set
// pass that does sets the cycle up again. So re-discretized is the default. The smoother and cycle figures
// below were taken with Galerkin operators; with re-discretized ones the same runs give the
// same counts to ±1 iteration.
// Either way, all levels' node filters are the caller's CG filters at update time: after a
// change of constraints the cycle must be updated before it is applied again.
//
// Smoothers (both polynomials in D⁻¹A with the filtered block diagonal D, so they are
// symmetric and parallel like an SpMV; the same one before and after the coarse correction
// makes the V-cycle symmetric, hence a valid CG preconditioner):
//  - Chebyshev: damps the eigenvalues of D⁻¹A in [λmax/range, λmax];
//  - damped block-Jacobi: ω = 4/(3 λmax), as the aggregation multigrid's.
// λmax by power iteration (refreshed every few updates: the corotated matrix changes slowly).
// Coloured Gauss–Seidel was not tried: BB control points of degree 3 touch ~100 neighbours,
// so a colouring needs many colours, each a sweep with poor locality.
// Measured with BM_DeformSolve (cubic 5184-tet beam, 85K unknowns, PCG to 1e-6 from zero),
// CG iterations for `sweeps` smoothing steps per side and c coarsest cycles (3 -> 2 -> 1),
// Galerkin coarse operators:
//                      c = 1    2    4    8   16
//   Chebyshev, 2 steps     33   26   20   16   15
//   Chebyshev, 1 step      38   31   29   27   27
//   damped Jacobi, 1 step  39   35   33   32   32
//   (c = 8: damped Jacobi 2 steps 24, Chebyshev 3 steps 14; 3 -> 1 directly, Chebyshev 2: 19)
// A cycle costs 2·sweeps fine-level products (+1 for CG's own), the degree-2 level ~18% of
// a fine product each, and the coarsest cycles little (the linear level has 1.3% of the fine
// blocks). So Chebyshev needs fewer fine products than damped Jacobi for the same residual
// (16 x 5 = 80 against 32 x 3 = 96 or 24 x 5 = 120; 3 steps: 14 x 7 = 98), the coarsest
// level is worth 8 cycles, and 3 -> 2 -> 1
// and 3 -> 1 cost about the same (16 x 5.7 against 19 x 5 products); the defaults are
// Chebyshev, 2 steps, 8 cycles. Timings on the shared 2-core machine vary ±30% with the
// other builds, which is why the choice rests on these counts.
//
// The coarsest level (degree 1) is solved with `coarseCycles` V-cycles of the aggregation
// multigrid (rigid-body modes; linalg/aggregation_multigrid.h). Its node i must be fine node
// i (the degree hierarchy numbers the mesh vertices first at every degree), so its positions
// are the first entries of the fine positions.
#pragma once

#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/task_system.h"
#include "linalg/aggregation_multigrid.h"
#include "linalg/block_sparse_matrix.h"
#include "linalg/node_prolongation.h"

namespace vp {

enum class PMultigridSmoother { Chebyshev, DampedJacobi };

struct PMultigridSettings {
  PMultigridSmoother smoother = PMultigridSmoother::Chebyshev;
  int sweeps = 2;                // smoothing steps before and after the coarse correction
  double chebyshevRange = 30.0;  // Chebyshev targets [λmax / range, λmax] of D⁻¹A
  int coarseCycles = 8;          // aggregation-multigrid V-cycles on the coarsest level
};

class PMultigrid {
 public:
  // prolongations[l] maps level l+1 to level l; level 0 is `fine`.
  // Galerkin coarse operators (rediscretized empty): builds the coarse patterns (the
  // symbolic products). Re-discretized ones: rediscretized[l-1] is level l's operator,
  // assembled by the caller at that level's degree (deform/degree_level_assembly.h); the
  // caller refills it before every update, which restricts it in place to the constrained
  // coarse space. Either way builds the coarsest level's multigrid.
  void build(const BlockSparseMatrix<double>& fine, std::vector<NodeProlongation> prolongations,
             const PMultigridSettings& settings = {}, std::vector<BlockSparseMatrix<double>*> rediscretized = {});

  // Recomputes filters, coarse operators, smoothers and the coarsest multigrid.
  // positions: 3 per fine node; filters: 9 per fine node (row-major projector) or nullptr.
  void update(TaskSystem& tasks, const BlockSparseMatrix<double>& fine, const double* positions,
              const double* filters);

  // z = V-cycle(r); r and z of size 3 * fine node count, not aliased.
  void apply(TaskSystem& tasks, const double* r, double* z);

  int levelCount() const { return static_cast<int>(levels_.size()); }
  bool rediscretized() const { return rediscretized_; }
  // The operator of level l (0: the fine matrix last passed to update).
  const BlockSparseMatrix<double>& levelMatrix(int l) const { return *levels_[l].matrix; }
  const PMultigridSettings& settings() const { return settings_; }

 private:
  enum : uint8_t { kIdentity = 0, kZero = 1, kGeneral = 2 };
  struct Level {
    int32_t nodes = 0;
    const BlockSparseMatrix<double>* matrix = nullptr;  // level 0: the caller's fine matrix
    BlockSparseMatrix<double>* coarse = nullptr;        // levels >= 1: &galerkin or the caller's
    BlockSparseMatrix<double> galerkin;                 // levels >= 1, Galerkin operators
    // From this level to the finer one (levels >= 1), and its transpose.
    NodeProlongation P;
    Array<int32_t> restrictStart, restrictFine;
    Array<double> restrictWeight;
    Array<double> filters;  // 9 per node
    Array<uint8_t> filterKind;
    Array<double> diagonalInverse;  // 9 per node, F D⁺ F
    double lambdaMax = 1.0;
    Array<double> rhs, z, residual, direction, product, post, smoothed;
  };

  void cycle(TaskSystem& tasks, int level, const double* r, double* z);
  // out = S rhs, S the smoothing polynomial; leaves rhs − A out in L.residual when asked.
  void smooth(TaskSystem& tasks, Level& L, const double* rhs, double* out, bool wantResidual);
  void coarseFilters(TaskSystem& tasks, int level);
  void coarseOperator(TaskSystem& tasks, int level);
  static void constrainRow(Level& L, int64_t row);
  void estimateLambdaMax(TaskSystem& tasks, Level& L);
  void coarsestSolve(TaskSystem& tasks, const double* r, double* z);

  PMultigridSettings settings_;
  bool rediscretized_ = false;
  std::vector<Level> levels_;
  AggregationMultigrid coarsest_;
  uint64_t updates_ = 0;
};

}  // namespace vp
