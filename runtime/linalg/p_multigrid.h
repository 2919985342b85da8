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
//    instead, the coarse nodes on a clamped face's edges stay free in a coarse problem that
//    believes the face moves with them: CG needs far more iterations on BM_DeformSolve and
//    the cycle alone does not converge (docs/choices.md, p-multigrid).
//  - Galerkin: A_c = P̃ᵀ A P̃ with the constrained prolongation P̃ = F_f P F_c, F_c the
//    projector onto the directions some fine reader may move in (the range of Σ F_i: I where
//    any reader is free, 0 where all are pinned). The product truncates coarse functions at
//    constrained fine nodes: a larger coarse space, the best correction in the energy norm
//    over it, at the price of one sparse triple product per level and update.
// Re-discretized is the default: a few more iterations than Galerkin for a much cheaper
// setup, which every active-set pass that changes the constraint set pays again
// (BM_DeformSolve, BM_DeformContact, BM_DeformQuadraticBeam against their Galerkin variants;
// figures in docs/choices.md, p-multigrid).
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
// The default smoother, `sweeps` and `coarseCycles` need the fewest fine-level products to
// reach the residual on BM_DeformSolve (CG iterations times 2·sweeps + 1 per cycle): counts
// rather than timings, which the shared machine makes noisy (docs/choices.md, p-multigrid).
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
