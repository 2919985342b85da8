// Aggregation multigrid for 3D elasticity, used as the CG preconditioner of the deformable
// solve (block-Jacobi alone needs hundreds of iterations on stiff meshes: its iteration count
// grows with the square root of the condition number, multigrid's does not).
//
// Hierarchy (built once from the matrix pattern, i.e. from the rest mesh's connectivity):
// nodes are grouped into aggregates (a node and its untaken neighbours, greedy, in index
// order: deterministic), aggregates again into coarser aggregates, until the coarsest level
// is small enough for a dense Cholesky factorization.
//
// Coarse spaces (rebuilt every step, because the corotated matrix changes): each aggregate
// carries the 6 rigid-body modes of its nodes about its centroid at the current positions
// (translations and infinitesimal rotations: the near-null space of elasticity), so the
// prolongation of level 0 is P_i = F_i [I | −[x_i − c]×] for fine node i, where F_i is the
// node's constraint filter (0 for pinned nodes, I − nnᵀ for sliding contacts); coarser levels
// map a child aggregate's rigid motion to its parent's. Coarse operators are Galerkin
// products PᵀAP, so every level solves a consistent, constrained problem ("plain" rather than
// smoothed aggregation: P stays block-diagonal and the products stay cheap).
//
// The V-cycle uses damped block-Jacobi smoothing (symmetric: one sweep before and one after
// the coarse correction, the same damping), so it is a symmetric positive preconditioner and
// CG stays valid. The damping is 4/(3 λmax) of D⁻¹A, with λmax from a few power iterations.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "core/allocator.h"
#include "core/task_system.h"
#include "linalg/block_sparse_matrix.h"

namespace vp {

class AggregationMultigrid {
 public:
  // Builds aggregates and coarse patterns from the fine matrix's pattern, with at least one
  // coarse level however small the mesh (the coarsest solve is over a level's aggregates)
  // unless no two nodes are joined, which a tet mesh never has.
  void build(const BlockSparseMatrix<double>& fine, int maxCoarsestNodes = kMaxCoarsestNodes);  // resets the hierarchy
  static constexpr int kMaxCoarsestNodes = 48;
  // The smoothers' dampings are estimated again every kDampingRefresh updates, counted from the
  // build or from restartDampingCount: the corotated matrix changes little from step to step,
  // and refreshing them at every update cost a third of the setup.
  static constexpr int kDampingRefresh = 8;
  // The next update estimates the dampings again and counts from there.
  void restartDampingCount() { updates_ = 0; }

  // Recomputes prolongations, coarse operators, smoothers and the coarsest factorization.
  // positions: 3 per fine node; filters: 9 per fine node (row-major 3x3 projector, the same
  // one CG applies), or nullptr for no constraints.
  void update(TaskSystem& tasks, const BlockSparseMatrix<double>& fine, const double* positions,
              const double* filters);

  // z = V-cycle(r); r and z of size 3 * fine node count.
  void apply(TaskSystem& tasks, const double* r, double* z);

  int levelCount() const { return static_cast<int>(levels_.size()) + 1; }
  int64_t coarsestSize() const { return coarsestSize_; }

 private:
  using Block6 = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;

  // Level l+1's unknowns: 6 per aggregate of level l's nodes.
  struct Level {
    int32_t fineNodes = 0, aggregates = 0;
    int fineBlock = 3;                      // 3 at level 0, 6 above
    Array<int32_t> aggregateOf;       // fine node -> aggregate
    Array<double> prolongation;             // fineBlock x 6 per fine node, row-major
    // Coarse operator (6x6 blocks) pattern and, per coarse block row, the fine blocks that
    // contribute: fine block k maps to coarse block coarseOfFine[k].
    Array<int32_t> rowStart, columns, diagonal;
    Array<int32_t> coarseOfFine;
    Array<int32_t> memberStart, members;  // fine nodes of each aggregate (CSR)
    Array<double> values;                   // 36 per coarse block
    Array<double> diagonalInverse;          // 36 per coarse node (smoother of this coarse level)
    Array<double> centroids;                // 3 per aggregate
    double damping = 0.5;                   // of the smoother on this coarse level
    // Scratch for the cycle.
    Array<double> residual, correction, rhs;
  };

  static void aggregate(int32_t nodes, const Array<int32_t>& rowStart, const Array<int32_t>& columns,
                        Array<int32_t>* aggregateOf, int32_t* count);

  // The stages of update(): the fine smoother's filtered block inverses; level l's centroids,
  // prolongation and Galerkin operator with its block inverses; every level's smoother
  // damping; the coarsest level's factorization.
  void invertFineDiagonal(TaskSystem& tasks, const BlockSparseMatrix<double>& fine, const double* filters);
  void updateLevel(TaskSystem& tasks, size_t l, const BlockSparseMatrix<double>& fine, const double* positions,
                   const double* filters);
  void refreshDampings(TaskSystem& tasks, const BlockSparseMatrix<double>& fine);
  void factorCoarsest();

  void cycle(TaskSystem& tasks, int level, const double* r, double* z);
  // y = A_l x on coarse level l (l >= 1: 6x6 blocks of levels_[l-1]).
  void coarseMultiply(TaskSystem& tasks, int level, const double* x, double* y) const;

  std::vector<Level> levels_;
  // Fine level smoother.
  Array<double> fineDiagonalInverse_;  // 9 per node (filtered)
  double fineDamping_ = 0.5;
  const BlockSparseMatrix<double>* fine_ = nullptr;
  const double* filters_ = nullptr;
  Array<double> fineResidual_, fineScratch_;
  // Coarsest level: dense Cholesky.
  Eigen::LDLT<Eigen::MatrixXd> coarsest_;
  uint64_t updates_ = 0;
  int64_t coarsestSize_ = 0;
};

}  // namespace vp
