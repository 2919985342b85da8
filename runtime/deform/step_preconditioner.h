// The preconditioner of a deformable's implicit solve (DeformableSolverSettings::preconditioner;
// Auto: a multigrid from kMultigridMinNodes nodes; below that block-Jacobi, but for linear
// elements the multigrid in the steps an elastic wave crosses many node spacings, chooseForStep):
// - block-Jacobi: the inverse of each node's 3x3 diagonal block, written by the assembly;
// - aggregation multigrid (linear elements): near-null-space aggregation on the fine matrix;
// - p-multigrid (degree 2 and 3): down the degrees to linear, on the Galerkin or the
//   re-discretized coarse operators.
// The multigrids bake the node constraints into their smoothers and coarse spaces, so they are
// refreshed whenever the matrix or the constraints change; block-Jacobi is not filtered and
// needs nothing.
#pragma once

#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "core/task_system.h"
#include "deform/deformable_desc.h"
#include "deform/degree_level_assembly.h"
#include "deform/node_constraints.h"
#include "linalg/aggregation_multigrid.h"
#include "linalg/block_sparse_matrix.h"
#include "linalg/p_multigrid.h"

namespace vp {

class StepPreconditioner {
 public:
  struct Mesh {
    int degree = 1;
    const int32_t* elementNodes = nullptr;  // nodes per element of `degree`, BB local order
    int64_t elements = 0;
    int32_t nodeCount = 0;
    const double* restVolumes = nullptr;
    double density = 0.0;
  };

  // Chooses and builds it; `matrix` must have its final pattern.
  Status build(const DeformableSolverSettings& settings, const Mesh& mesh, const BlockSparseMatrix<double>& matrix);
  // Auto on a linear mesh under kMultigridMinNodes: block-Jacobi for a step over which an
  // elastic wave crosses at most kMultigridWaveCrossings node spacings, else aggregation
  // multigrid (built the first time it is needed). Block-Jacobi's CG iterations grow with the
  // crossings, the multigrid's do not: a body paced by a liquid steps several frames at once.
  // A fixed choice stays as it is.
  void chooseForStep(double waveCrossings, const BlockSparseMatrix<double>& matrix);
  // The preconditioner of the step being solved (build's choice until a step chose).
  Preconditioner kind() const { return kind_; }
  // Block-Jacobi's inverse diagonal block of a node (9, row-major), for the assembly to write.
  double* inverseDiagonal(int64_t node) { return &diagInverse_[9 * node]; }
  // After the matrix or the constraints changed: the multigrids' filters and setup (the
  // re-discretized levels from the fine assembly's rotated gradient pairs, their mass scaled
  // as the fine system's). Nothing for block-Jacobi.
  void refresh(TaskSystem& tasks, const BlockSparseMatrix<double>& matrix, const double* positions,
               const NodeConstraints& held, const double* gradientPairs, double massScale);
  bool needsRefresh() const { return kind_ != Preconditioner::BlockJacobi; }
  void apply(TaskSystem& tasks, const double* r, double* z);
  // The density changed by `ratio` (the re-discretized levels' masses follow).
  void scaleMasses(double ratio);

 private:
  Preconditioner kind_ = Preconditioner::BlockJacobi;
  // Auto below kMultigridMinNodes: the multigrid for long steps (BlockJacobi: the choice is fixed).
  Preconditioner longStepKind_ = Preconditioner::BlockJacobi;
  int32_t nodeCount_ = 0;
  Array<double> diagInverse_;  // 9 per node
  AggregationMultigrid multigrid_;
  PMultigrid pMultigrid_;
  std::vector<DegreeLevelAssembly> degreeLevels_;  // p-multigrid's re-discretized levels, if chosen
  Array<double> nodeFilters_;  // 9 per node: the constraints as 3x3 projectors, for the multigrids
};

}  // namespace vp
