// Re-discretized p-multigrid levels (linalg/p_multigrid.h): the backward-Euler step matrix of
// a coarser BB degree on the same mesh, assembled directly at that degree,
//   A_m = s_M · M_m + Σ_e R_e K_e^m R_eᵀ · s_K,
// with the fine level's per-element rotations R_e and its integrator scalings (s_M = 1 + hα on
// the mass, s_K = hβ + h² on the stiffness), M_m the lumped BB mass of degree m.
//
// The rotations and s_K come in through the fine assembly's rotated gradient pairs
// (deform/bb_rotated_stiffness.h): P_cd depends on the degree only through the factor
// 3n/(4n² − 1), so degree m's blocks are the same 16 pairs per element, rescaled, summed with
// degree m's G_{m−1} weights. No element matrix is formed and no rotation is recomputed.
//
// Exactness: degree elevation E represents a degree-m field exactly at degree n, so per
// element Eᵀ K_e^n E = K_e^m; and R_e acts per node, commuting with E. Hence the stiffness
// part equals the Galerkin product Pᵀ (Σ_e R_e K_e^n R_eᵀ) P for any per-element rotations.
// The mass part does not: the lumped degree-n mass elevated (Pᵀ M_n P) is not the lumped
// degree-m mass (both carry ρV per element; tests/unit/deform_degree_level_assembly_test.cpp).
#pragma once

#include <cstdint>

#include "core/allocator.h"
#include "core/task_system.h"
#include "deform/bb_rotated_stiffness.h"
#include "deform/degree_hierarchy.h"
#include "deform/element_incidence.h"
#include "linalg/block_sparse_matrix.h"

namespace vp {

class DegreeLevelAssembly {
 public:
  // level: a level of a DegreeHierarchy below the fine degree (level.degree < fineDegree);
  // restVolumes: one per element; density ρ of the lumped mass. Builds the pattern (every
  // pair of nodes sharing an element: the same as the Galerkin product's) and the lumped mass.
  void build(const DegreeLevel& level, int fineDegree, const double* restVolumes, int64_t elementCount,
             double density);

  // Fills matrix() from the fine assembly's gradient pairs (144 per element, as
  // bbRotatedGradientPairs made them for fineDegree, with the stiffness scale in them) and
  // the mass scale. Parallel over rows, deterministic for any worker count.
  void assemble(TaskSystem& tasks, const double* gradientPairs, double massScale);

  int degree() const { return degree_; }
  BlockSparseMatrix<double>& matrix() { return matrix_; }
  const BlockSparseMatrix<double>& matrix() const { return matrix_; }
  const Array<double>& nodeMasses() const { return mass_; }  // lumped, unscaled
  void scaleMasses(double factor) {  // a new density: the lumped mass is linear in it
    for (double& m : mass_) m *= factor;
  }

 private:
  int degree_ = 1;
  int nodesPerElement_ = 4;
  BBStiffnessTerms terms_;  // degree_'s G weights times the pair rescaling from fineDegree
  Array<int32_t> elementNodes_;
  ElementIncidence incidence_;
  Array<double> mass_;
  BlockSparseMatrix<double> matrix_;
  Array<int32_t> scatter_;
};

}  // namespace vp
