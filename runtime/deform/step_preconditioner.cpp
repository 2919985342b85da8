#include "deform/step_preconditioner.h"

#include "core/parallel_for.h"
#include "deform/degree_hierarchy.h"

namespace vp {
namespace {

// The p-multigrid levels below each degree. Cubic goes through quadratic: 3->1 directly
// leaves too much for the smoother (BM_DeformSolve; docs/choices.md, p-multigrid).
std::vector<int> pMultigridDegrees(int degree) {
  if (degree == 3) return {3, 2, 1};
  return {degree, 1};
}

// One Chebyshev step per side for quadratic elements: at the step's usual tolerance
// (warm-started) the coarse correction does most of the work and a second step costs more
// fine-level products than the iterations it saves; cubic keeps two (BM_DeformQuadraticBeam,
// BM_DeformSolve; figures in docs/choices.md, p-multigrid).
PMultigridSettings pMultigridSettings(int degree) {
  PMultigridSettings settings;
  if (degree == 2) settings.sweeps = 1;
  return settings;
}

Preconditioner chosen(Preconditioner asked, int degree, int32_t nodeCount) {
  const bool large = nodeCount >= kMultigridMinNodes;
  if (degree > 1 && (asked == Preconditioner::PMultigrid || (asked == Preconditioner::Auto && large)))
    return Preconditioner::PMultigrid;
  if (asked == Preconditioner::Multigrid || asked == Preconditioner::PMultigrid || (asked == Preconditioner::Auto && large))
    return Preconditioner::Multigrid;
  return Preconditioner::BlockJacobi;
}

}  // namespace

Status StepPreconditioner::build(const DeformableSolverSettings& settings, const Mesh& mesh,
                                 const BlockSparseMatrix<double>& matrix) {
  kind_ = chosen(settings.preconditioner, mesh.degree, mesh.nodeCount);
  // Linear elements only: on the default scene's small cubic jelly p-multigrid's setup cost more
  // than the block-Jacobi iterations it saved (docs/choices.md, Preconditioner).
  const bool autoSmall = settings.preconditioner == Preconditioner::Auto && kind_ == Preconditioner::BlockJacobi;
  longStepKind_ = autoSmall && mesh.degree == 1 ? Preconditioner::Multigrid : Preconditioner::BlockJacobi;
  nodeCount_ = mesh.nodeCount;
  if (kind_ == Preconditioner::Multigrid) multigrid_.build(matrix);
  if (kind_ == Preconditioner::PMultigrid) {
    DegreeHierarchy hierarchy;
    VP_TRY(buildDegreeHierarchy(pMultigridDegrees(mesh.degree), mesh.elementNodes, mesh.elements, mesh.nodeCount,
                                &hierarchy));
    std::vector<BlockSparseMatrix<double>*> rediscretized;
    if (settings.pMultigridCoarseOperator == PMultigridCoarseOperator::Rediscretized) {
      degreeLevels_.resize(hierarchy.levels.size() - 1);
      for (size_t l = 1; l < hierarchy.levels.size(); ++l) {
        degreeLevels_[l - 1].build(hierarchy.levels[l], mesh.degree, mesh.restVolumes, mesh.elements, mesh.density);
        rediscretized.push_back(&degreeLevels_[l - 1].matrix());
      }
    }
    pMultigrid_.build(matrix, std::move(hierarchy.prolongations), pMultigridSettings(mesh.degree),
                      std::move(rediscretized));
  }
  if (needsRefresh()) nodeFilters_.assign(9 * static_cast<size_t>(mesh.nodeCount), 0.0);
  diagInverse_.resize(9 * static_cast<size_t>(mesh.nodeCount));
  return Status::Ok;
}

void StepPreconditioner::chooseForStep(double waveCrossings, const BlockSparseMatrix<double>& matrix) {
  if (longStepKind_ == Preconditioner::BlockJacobi) return;
  if (!(waveCrossings > kMultigridWaveCrossings)) {
    kind_ = Preconditioner::BlockJacobi;
    return;
  }
  if (nodeFilters_.empty()) {  // the first long step
    multigrid_.build(matrix);
    nodeFilters_.assign(9 * static_cast<size_t>(nodeCount_), 0.0);
  }
  kind_ = longStepKind_;
  // Dampings from this step's matrix, kept for its contact passes' updates: which earlier steps
  // were long is not part of a saved world's state, and a restored one must continue bitwise.
  multigrid_.restartDampingCount();
}

void StepPreconditioner::refresh(TaskSystem& tasks, const BlockSparseMatrix<double>& matrix, const double* positions,
                                 const NodeConstraints& held, const double* gradientPairs, double massScale) {
  if (!needsRefresh()) return;
  held.projectors(tasks, nodeFilters_.data());
  if (kind_ == Preconditioner::Multigrid) return multigrid_.update(tasks, matrix, positions, nodeFilters_.data());
  // Re-discretized levels: this step's rotations and scalings, from the fine assembly (and
  // afresh for every update, which constrains them in place).
  for (DegreeLevelAssembly& level : degreeLevels_) level.assemble(tasks, gradientPairs, massScale);
  pMultigrid_.update(tasks, matrix, positions, nodeFilters_.data());
}

void StepPreconditioner::apply(TaskSystem& tasks, const double* r, double* z) {
  if (kind_ == Preconditioner::Multigrid) return multigrid_.apply(tasks, r, z);
  if (kind_ == Preconditioner::PMultigrid) return pMultigrid_.apply(tasks, r, z);
  parallelFor(tasks, nodeCount_, 1024, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const double* m = &diagInverse_[9 * i];
      const double* ri = r + 3 * i;
      for (int k = 0; k < 3; ++k) z[3 * i + k] = m[3 * k] * ri[0] + m[3 * k + 1] * ri[1] + m[3 * k + 2] * ri[2];
    }
  });
}

void StepPreconditioner::scaleMasses(double ratio) {
  for (DegreeLevelAssembly& level : degreeLevels_) level.scaleMasses(ratio);
}

}  // namespace vp
