#include "deform/bb_evaluation.h"

#include <cassert>

#include "deform/bb_multi_index.h"

namespace vp {
namespace {

// λ^k for k = 0..3 by repeated multiplication (std::pow is slower and not needed).
inline double ipow(double x, int k) {
  double r = 1.0;
  for (int i = 0; i < k; ++i) r *= x;
  return r;
}

inline double monomial(const BBMultiIndex& alpha, const double bary[4]) {
  return ipow(bary[0], alpha.a[0]) * ipow(bary[1], alpha.a[1]) * ipow(bary[2], alpha.a[2]) *
         ipow(bary[3], alpha.a[3]);
}

}  // namespace

void bbBasis(int degree, const double bary[4], double* basis) {
  assert(degree >= 1 && degree <= kBBMaxDegree);
  const BBMultiIndex* nodes = bbMultiIndices(degree);
  for (int k = 0; k < bbNodeCount(degree); ++k)
    basis[k] = bbMultinomial(nodes[k]) * monomial(nodes[k], bary);
}

void bbBasisBaryDerivatives(int degree, const double bary[4], double* derivatives) {
  assert(degree >= 1 && degree <= kBBMaxDegree);
  const BBMultiIndex* nodes = bbMultiIndices(degree);
  for (int k = 0; k < bbNodeCount(degree); ++k) {
    for (int c = 0; c < 4; ++c) {
      if (nodes[k].a[c] == 0) {
        derivatives[4 * k + c] = 0.0;
        continue;
      }
      BBMultiIndex lower = nodes[k];
      --lower.a[c];
      derivatives[4 * k + c] = degree * bbMultinomial(lower) * monomial(lower, bary);
    }
  }
}

void bbEvaluate(int degree, const double* coeffs, const double bary[4], double value[3]) {
  double basis[kBBMaxNodes];
  bbBasis(degree, bary, basis);
  value[0] = value[1] = value[2] = 0.0;
  for (int k = 0; k < bbNodeCount(degree); ++k)
    for (int a = 0; a < 3; ++a) value[a] += basis[k] * coeffs[3 * k + a];
}

void bbEvaluateGradient(int degree, const double* coeffs, const double bary[4],
                        const double baryGrad[12], double grad[9]) {
  double dB[4 * kBBMaxNodes];
  bbBasisBaryDerivatives(degree, bary, dB);
  // First ∂value/∂λ_c (3 x 4), then the chain rule through the constant ∇λ_c.
  double dValue[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  for (int k = 0; k < bbNodeCount(degree); ++k)
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 4; ++c) dValue[a][c] += coeffs[3 * k + a] * dB[4 * k + c];
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int c = 0; c < 4; ++c) s += dValue[a][c] * baryGrad[3 * c + j];
      grad[3 * a + j] = s;
    }
}

Status bbElevationRows(int fromDegree, BBElevationRow* rows) {
  if (fromDegree < 1 || fromDegree >= kBBMaxDegree)
    return fail(Status::InvalidArgument, "bbElevationRows: fromDegree = %d, expected 1 or 2",
                fromDegree);
  const int fine = fromDegree + 1;
  const BBMultiIndex* fineNodes = bbMultiIndices(fine);
  for (int k = 0; k < bbNodeCount(fine); ++k) {
    BBElevationRow& row = rows[k];
    row.count = 0;
    for (int i = 0; i < 4; ++i) {
      const int beta_i = fineNodes[k].a[i];
      if (beta_i == 0) continue;
      int lower[4] = {fineNodes[k].a[0], fineNodes[k].a[1], fineNodes[k].a[2], fineNodes[k].a[3]};
      --lower[i];
      row.node[row.count] = bbNodeIndex(lower);
      row.weight[row.count] = static_cast<double>(beta_i) / fine;
      ++row.count;
    }
    for (int i = row.count; i < 4; ++i) {
      row.node[i] = -1;
      row.weight[i] = 0.0;
    }
  }
  return Status::Ok;
}

void bbElevate(int fromDegree, const double* coarse, double* fine) {
  assert(fromDegree >= 1 && fromDegree < kBBMaxDegree);
  BBElevationRow rows[kBBMaxNodes];
  bbElevationRows(fromDegree, rows);
  for (int k = 0; k < bbNodeCount(fromDegree + 1); ++k)
    for (int a = 0; a < 3; ++a) {
      double s = 0.0;
      for (int m = 0; m < rows[k].count; ++m) s += rows[k].weight[m] * coarse[3 * rows[k].node[m] + a];
      fine[3 * k + a] = s;
    }
}

}  // namespace vp
