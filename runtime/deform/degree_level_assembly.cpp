#include "deform/degree_level_assembly.h"

#include <algorithm>

#include "core/parallel_for.h"
#include "deform/bb_multi_index.h"

namespace vp {
namespace {

// The degree factor 3n/(4n² − 1) of the gradient pairs (bb_rotated_stiffness.h).
double pairFactor(int degree) { return 3.0 * degree / (4.0 * degree * degree - 1.0); }

}  // namespace

void DegreeLevelAssembly::build(const DegreeLevel& level, int fineDegree, const double* restVolumes,
                                int64_t elementCount, double density) {
  degree_ = level.degree;
  nodesPerElement_ = bbNodeCount(degree_);
  const int N = nodesPerElement_;
  terms_ = bbStiffnessTerms(degree_);
  const double rescale = pairFactor(degree_) / pairFactor(fineDegree);
  for (double& w : terms_.weight) w *= rescale;
  elementNodes_.assign(level.elementNodes.begin(), level.elementNodes.end());
  incidence_.build(level.nodeCount, elementNodes_.data(), elementCount, N);
  // Lumped BB mass: every Bernstein function of degree m integrates to V / C(m+3, 3)
  // (bb_element_matrices.h, bbLumpedMass).
  mass_.assign(static_cast<size_t>(level.nodeCount), 0.0);
  const double share = density / bbBinomial(degree_ + 3, 3);
  for (int64_t e = 0; e < elementCount; ++e)
    for (int a = 0; a < N; ++a) mass_[elementNodes_[N * e + a]] += share * restVolumes[e];
  buildElementPattern(level.nodeCount, elementNodes_.data(), elementCount, N, &matrix_, &scatter_);
}

void DegreeLevelAssembly::assemble(TaskSystem& tasks, const double* gradientPairs, double massScale) {
  const int N = nodesPerElement_;
  const kernels::BBStiffnessTermsView terms = terms_.view();
  parallelFor(tasks, matrix_.blockRows, 64, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      std::fill(matrix_.values.begin() + 9 * static_cast<int64_t>(matrix_.rowStart[i]),
                matrix_.values.begin() + 9 * static_cast<int64_t>(matrix_.rowStart[i + 1]), 0.0);
      for (int32_t k = incidence_.start[i]; k < incidence_.start[i + 1]; ++k) {
        const int64_t e = incidence_.element[k];
        const int a = incidence_.corner[k];
        const int32_t* scatter = &scatter_[N * N * e + N * a];
        for (int b = 0; b < N; ++b)
          kernels::addBBRotatedBlock(terms, gradientPairs + 144 * e, N, a, b,
                            &matrix_.values[9 * static_cast<int64_t>(scatter[b])]);
      }
      double* diagonal = &matrix_.values[9 * static_cast<int64_t>(matrix_.diagonal[i])];
      for (int k = 0; k < 3; ++k) diagonal[4 * k] += massScale * mass_[i];
    }
  });
}

}  // namespace vp
