#include "linalg/aggregation_multigrid.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "linalg/symmetric_pseudo_inverse.h"

namespace vp {
namespace {

using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using Mat36 = Eigen::Matrix<double, 3, 6, Eigen::RowMajor>;
using Mat6R = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;

Mat3R skew(const Eigen::Vector3d& r) {
  Mat3R s;
  s << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return s;
}

constexpr int64_t kRowGrain = 256;
constexpr int kPowerIterations = 6;

}  // namespace

void AggregationMultigrid::aggregate(int32_t nodes, const Array<int32_t>& rowStart,
                                     const Array<int32_t>& columns, Array<int32_t>* aggregateOf,
                                     int32_t* count) {
  Array<int32_t>& agg = *aggregateOf;
  agg.assign(static_cast<size_t>(nodes), -1);
  int32_t next = 0;
  // 1. Seeds: a node whose neighbours are all free takes them all.
  for (int32_t i = 0; i < nodes; ++i) {
    bool free = agg[i] < 0;
    for (int32_t k = rowStart[i]; k < rowStart[i + 1] && free; ++k) free = agg[columns[k]] < 0;
    if (!free) continue;
    for (int32_t k = rowStart[i]; k < rowStart[i + 1]; ++k) agg[columns[k]] = next;
    ++next;
  }
  // 2. Leftovers join a neighbouring aggregate (the first in column order: deterministic).
  Array<int32_t> joined(agg);
  for (int32_t i = 0; i < nodes; ++i) {
    if (agg[i] >= 0) continue;
    for (int32_t k = rowStart[i]; k < rowStart[i + 1]; ++k)
      if (agg[columns[k]] >= 0) {
        joined[i] = agg[columns[k]];
        break;
      }
  }
  agg.swap(joined);
  // 3. Isolated nodes become their own aggregate.
  for (int32_t i = 0; i < nodes; ++i)
    if (agg[i] < 0) agg[i] = next++;
  *count = next;
}

void AggregationMultigrid::build(const BlockSparseMatrix<double>& fine, int maxCoarsestNodes) {
  levels_.clear();
  updates_ = 0;
  Array<int32_t> rowStart(fine.rowStart.begin(), fine.rowStart.end());
  Array<int32_t> columns(fine.columns.begin(), fine.columns.end());
  int32_t nodes = fine.blockRows;
  int block = 3;
  while (nodes > maxCoarsestNodes || levels_.empty()) {
    Level L;
    L.fineNodes = nodes;
    L.fineBlock = block;
    aggregate(nodes, rowStart, columns, &L.aggregateOf, &L.aggregates);
    if (L.aggregates >= nodes) break;  // no coarsening possible (disconnected nodes)
    // Members of each aggregate.
    L.memberStart.assign(static_cast<size_t>(L.aggregates) + 1, 0);
    for (int32_t i = 0; i < nodes; ++i) L.memberStart[L.aggregateOf[i] + 1]++;
    for (int32_t a = 0; a < L.aggregates; ++a) L.memberStart[a + 1] += L.memberStart[a];
    L.members.resize(static_cast<size_t>(nodes));
    Array<int32_t> fill(L.memberStart.begin(), L.memberStart.end() - 1);
    for (int32_t i = 0; i < nodes; ++i) L.members[fill[L.aggregateOf[i]]++] = i;
    // Coarse pattern: aggregate pairs joined by a fine block.
    std::vector<Array<int32_t>> neighbours(static_cast<size_t>(L.aggregates));
    for (int32_t i = 0; i < nodes; ++i)
      for (int32_t k = rowStart[i]; k < rowStart[i + 1]; ++k)
        neighbours[L.aggregateOf[i]].push_back(L.aggregateOf[columns[k]]);
    L.rowStart.assign(static_cast<size_t>(L.aggregates) + 1, 0);
    for (int32_t a = 0; a < L.aggregates; ++a) {
      auto& n = neighbours[a];
      std::sort(n.begin(), n.end());
      n.erase(std::unique(n.begin(), n.end()), n.end());
      L.columns.insert(L.columns.end(), n.begin(), n.end());
      L.rowStart[a + 1] = static_cast<int32_t>(L.columns.size());
    }
    auto find = [&](int32_t row, int32_t col) {
      auto b = L.columns.begin() + L.rowStart[row], e = L.columns.begin() + L.rowStart[row + 1];
      return static_cast<int32_t>(std::lower_bound(b, e, col) - L.columns.begin());
    };
    L.diagonal.resize(static_cast<size_t>(L.aggregates));
    for (int32_t a = 0; a < L.aggregates; ++a) L.diagonal[a] = find(a, a);
    L.coarseOfFine.resize(columns.size());
    for (int32_t i = 0; i < nodes; ++i)
      for (int32_t k = rowStart[i]; k < rowStart[i + 1]; ++k)
        L.coarseOfFine[k] = find(L.aggregateOf[i], L.aggregateOf[columns[k]]);
    L.prolongation.assign(static_cast<size_t>(nodes) * block * 6, 0.0);
    L.values.assign(L.columns.size() * 36, 0.0);
    L.diagonalInverse.assign(static_cast<size_t>(L.aggregates) * 36, 0.0);
    L.centroids.assign(static_cast<size_t>(L.aggregates) * 3, 0.0);
    L.residual.assign(static_cast<size_t>(nodes) * block, 0.0);
    L.correction.assign(static_cast<size_t>(L.aggregates) * 6, 0.0);
    L.rhs.assign(static_cast<size_t>(L.aggregates) * 6, 0.0);
    rowStart = L.rowStart;
    columns = L.columns;
    nodes = L.aggregates;
    block = 6;
    levels_.push_back(std::move(L));
  }
  const size_t n3 = 3 * static_cast<size_t>(fine.blockRows);
  fineDiagonalInverse_.assign(9 * static_cast<size_t>(fine.blockRows), 0.0);
  fineResidual_.assign(n3, 0.0);
  fineScratch_.assign(n3, 0.0);
}

void AggregationMultigrid::coarseMultiply(TaskSystem& tasks, int level, const double* x, double* y) const {
  const Level& L = levels_[level - 1];
  parallelFor(tasks, L.aggregates, kRowGrain / 4, [&](int64_t begin, int64_t end) {
    for (int64_t a = begin; a < end; ++a) {
      Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
      for (int32_t k = L.rowStart[a]; k < L.rowStart[a + 1]; ++k)
        sum += Eigen::Map<const Mat6R>(&L.values[36 * static_cast<int64_t>(k)]) *
               Eigen::Map<const Eigen::Matrix<double, 6, 1>>(x + 6 * static_cast<int64_t>(L.columns[k]));
      Eigen::Map<Eigen::Matrix<double, 6, 1>>(y + 6 * a) = sum;
    }
  });
}

void AggregationMultigrid::update(TaskSystem& tasks, const BlockSparseMatrix<double>& fine, const double* positions,
                                  const double* filters) {
  fine_ = &fine;
  filters_ = filters;
  invertFineDiagonal(tasks, fine, filters);
  for (size_t l = 0; l < levels_.size(); ++l) updateLevel(tasks, l, fine, positions, filters);
  if (updates_++ % kDampingRefresh == 0) refreshDampings(tasks, fine);
  factorCoarsest();
}

void AggregationMultigrid::invertFineDiagonal(TaskSystem& tasks, const BlockSparseMatrix<double>& fine,
                                              const double* filters) {
  // Fine smoother: F D⁻¹ F per node (symmetric, zero on pinned directions).
  parallelFor(tasks, fine.blockRows, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      Mat3R inv = Eigen::Map<const Mat3R>(&fine.values[9 * static_cast<int64_t>(fine.diagonal[i])]).inverse();
      if (filters) {
        const Eigen::Map<const Mat3R> F(filters + 9 * i);
        inv = F * inv * F;
      }
      Eigen::Map<Mat3R> out(&fineDiagonalInverse_[9 * i]);
      out = inv;
    }
  });
}

void AggregationMultigrid::updateLevel(TaskSystem& tasks, size_t l, const BlockSparseMatrix<double>& fine,
                                       const double* positions, const double* filters) {
  Level& L = levels_[l];
  const int b = L.fineBlock;
  // Centroids of this level's aggregates, from the positions of their members.
  const double* memberPositions = l == 0 ? positions : levels_[l - 1].centroids.data();
  for (int32_t a = 0; a < L.aggregates; ++a) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int32_t m = L.memberStart[a]; m < L.memberStart[a + 1]; ++m)
      c += Eigen::Map<const Eigen::Vector3d>(memberPositions + 3 * static_cast<int64_t>(L.members[m]));
    Eigen::Map<Eigen::Vector3d>(&L.centroids[3 * a]) = c / double(L.memberStart[a + 1] - L.memberStart[a]);
  }
  // Prolongation blocks: rigid modes about the centroid (filtered at level 0).
  parallelFor(tasks, L.fineNodes, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const Eigen::Vector3d r = Eigen::Map<const Eigen::Vector3d>(memberPositions + 3 * i) -
                                Eigen::Map<const Eigen::Vector3d>(&L.centroids[3 * L.aggregateOf[i]]);
      if (b == 3) {
        Mat36 P;
        P << Mat3R::Identity(), -skew(r);
        if (filters) P = Eigen::Map<const Mat3R>(filters + 9 * i) * P;
        Eigen::Map<Mat36>(&L.prolongation[18 * i]) = P;
      } else {
        Mat6R P = Mat6R::Identity();
        P.topRightCorner<3, 3>() = -skew(r);
        Eigen::Map<Mat6R>(&L.prolongation[36 * i]) = P;
      }
    }
  });
  // Nodes whose filter is the identity (most of them) take the cheap product below.
  Array<uint8_t> unfiltered(static_cast<size_t>(L.fineNodes), 0);
  if (l == 0)
    for (int32_t i = 0; i < L.fineNodes; ++i)
      unfiltered[i] = !filters || Eigen::Map<const Mat3R>(filters + 9 * static_cast<int64_t>(i)).isIdentity(0.0);
  // Galerkin product, one coarse row at a time (each row owned by one task: no races).
  const double* fineValues = l == 0 ? fine.values.data() : levels_[l - 1].values.data();
  const int32_t* fineRowStart = l == 0 ? fine.rowStart.data() : levels_[l - 1].rowStart.data();
  const int32_t* fineColumns = l == 0 ? fine.columns.data() : levels_[l - 1].columns.data();
  parallelFor(tasks, L.aggregates, 16, [&](int64_t begin, int64_t end) {
    for (int64_t a = begin; a < end; ++a) {
      for (int32_t k = L.rowStart[a]; k < L.rowStart[a + 1]; ++k)
        Eigen::Map<Mat6R>(&L.values[36 * static_cast<int64_t>(k)]).setZero();
      for (int32_t m = L.memberStart[a]; m < L.memberStart[a + 1]; ++m) {
        const int32_t i = L.members[m];
        for (int32_t k = fineRowStart[i]; k < fineRowStart[i + 1]; ++k) {
          const int32_t j = fineColumns[k];
          Eigen::Map<Mat6R> target(&L.values[36 * static_cast<int64_t>(L.coarseOfFine[k])]);
          if (b == 3) {
            const Eigen::Map<const Mat36> Pi(&L.prolongation[18 * static_cast<int64_t>(i)]);
            const Eigen::Map<const Mat36> Pj(&L.prolongation[18 * static_cast<int64_t>(j)]);
            const Eigen::Map<const Mat3R> A(fineValues + 9 * static_cast<int64_t>(k));
            if (unfiltered[i] && unfiltered[j]) {
              // P = [I | −[r]×] for free nodes: the product needs three 3x3 products, not
              // the 6x3·3x3·3x6 of the general case.
              const Mat3R AH = A * Pj.rightCols<3>();
              const Mat3R HtA = Pi.rightCols<3>().transpose() * A;
              target.topLeftCorner<3, 3>() += A;
              target.topRightCorner<3, 3>() += AH;
              target.bottomLeftCorner<3, 3>() += HtA;
              target.bottomRightCorner<3, 3>().noalias() += Pi.rightCols<3>().transpose() * AH;
            } else {
              target.noalias() += Pi.transpose() * (A * Pj);
            }
          } else {
            const Eigen::Map<const Mat6R> Pi(&L.prolongation[36 * static_cast<int64_t>(i)]);
            const Eigen::Map<const Mat6R> Pj(&L.prolongation[36 * static_cast<int64_t>(j)]);
            const Eigen::Map<const Mat6R> A(fineValues + 36 * static_cast<int64_t>(k));
            target.noalias() += Pi.transpose() * (A * Pj);
          }
        }
      }
      Eigen::Map<Mat6R>(&L.diagonalInverse[36 * a]) =
          symmetricPseudoInverse<6>(Eigen::Map<const Mat6R>(&L.values[36 * static_cast<int64_t>(L.diagonal[a])]));
    }
  });
}

void AggregationMultigrid::refreshDampings(TaskSystem& tasks, const BlockSparseMatrix<double>& fine) {
  // Smoother damping 4/(3 λmax(D⁻¹A)) per level: the choice that damps the upper two
  // thirds of the spectrum best for Jacobi; λmax by power iteration from a fixed vector.
  for (size_t level = 0; level < levels_.size(); ++level) {
    const int64_t n = level == 0 ? 3 * static_cast<int64_t>(fine.blockRows) : 6 * levels_[level - 1].aggregates;
    Array<double> v(static_cast<size_t>(n)), w(static_cast<size_t>(n));
    for (int64_t i = 0; i < n; ++i) v[i] = 1.0 + 0.01 * static_cast<double>(i % 7);
    double lambda = 1.0;
    for (int it = 0; it < kPowerIterations; ++it) {
      if (level == 0) {
        fine.multiply(tasks, v.data(), w.data());
        for (int32_t i = 0; i < fine.blockRows; ++i) {
          Eigen::Map<Eigen::Vector3d> vi(&v[3 * i]);
          vi = Eigen::Map<const Mat3R>(&fineDiagonalInverse_[9 * i]) * Eigen::Map<const Eigen::Vector3d>(&w[3 * i]);
        }
      } else {
        const Level& L = levels_[level - 1];
        coarseMultiply(tasks, static_cast<int>(level), v.data(), w.data());
        for (int32_t a = 0; a < L.aggregates; ++a) {
          Eigen::Map<Eigen::Matrix<double, 6, 1>> va(&v[6 * a]);
          va = Eigen::Map<const Mat6R>(&L.diagonalInverse[36 * a]) * Eigen::Map<const Eigen::Matrix<double, 6, 1>>(&w[6 * a]);
        }
      }
      double norm = 0.0;
      for (double x : v) norm += x * x;
      norm = std::sqrt(norm);
      if (!(norm > 0.0)) break;
      lambda = norm;  // |D⁻¹A v| for the unit v of the previous iteration
      for (double& x : v) x /= norm;
    }
    const double damping = 4.0 / (3.0 * 1.05 * std::max(lambda, 1e-12));
    if (level == 0) fineDamping_ = damping;
    else levels_[level - 1].damping = damping;
  }
}

void AggregationMultigrid::factorCoarsest() {
  // Coarsest level: dense LDLT, with a whisper of regularization so aggregates made only of
  // pinned nodes (zero rows) do not break the factorization; their right-hand sides are zero.
  const Level* last = levels_.empty() ? nullptr : &levels_.back();
  if (last) {
    const int64_t n = 6 * static_cast<int64_t>(last->aggregates);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
    for (int32_t a = 0; a < last->aggregates; ++a)
      for (int32_t k = last->rowStart[a]; k < last->rowStart[a + 1]; ++k)
        dense.block<6, 6>(6 * a, 6 * last->columns[k]) = Eigen::Map<const Mat6R>(&last->values[36 * static_cast<int64_t>(k)]);
    const double scale = std::max(dense.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    dense.diagonal().array() += 1e-12 * scale;
    coarsest_.compute(dense);
    coarsestSize_ = n;
  }
}

void AggregationMultigrid::cycle(TaskSystem& tasks, int level, const double* r, double* z) {
  if (level == static_cast<int>(levels_.size())) {
    const int64_t n = coarsestSize_;
    Eigen::Map<Eigen::VectorXd>(z, n) = coarsest_.solve(Eigen::Map<const Eigen::VectorXd>(r, n));
    return;
  }
  Level& L = levels_[level];
  const int b = L.fineBlock;
  const int64_t nodes = L.fineNodes;
  double* res = level == 0 ? fineResidual_.data() : L.residual.data();
  auto multiply = [&](const double* x, double* y) {
    if (level == 0) fine_->multiply(tasks, x, y);
    else coarseMultiply(tasks, level, x, y);
  };
  const double damping = level == 0 ? fineDamping_ : levels_[level - 1].damping;
  const double* dinv = level == 0 ? fineDiagonalInverse_.data() : levels_[level - 1].diagonalInverse.data();
  // z += ω D⁻¹ (r − A z), with A z given in `az` (or z = 0 when az is null).
  auto smooth = [&](const double* az) {
    parallelFor(tasks, nodes, kRowGrain, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        if (b == 3) {
          Eigen::Vector3d e = Eigen::Map<const Eigen::Vector3d>(r + 3 * i);
          if (az) e -= Eigen::Map<const Eigen::Vector3d>(az + 3 * i);
          Eigen::Vector3d dz = damping * (Eigen::Map<const Mat3R>(dinv + 9 * i) * e);
          if (az) Eigen::Map<Eigen::Vector3d>(z + 3 * i) += dz;
          else Eigen::Map<Eigen::Vector3d>(z + 3 * i) = dz;
        } else {
          Eigen::Matrix<double, 6, 1> e = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(r + 6 * i);
          if (az) e -= Eigen::Map<const Eigen::Matrix<double, 6, 1>>(az + 6 * i);
          Eigen::Matrix<double, 6, 1> dz = damping * (Eigen::Map<const Mat6R>(dinv + 36 * i) * e);
          if (az) Eigen::Map<Eigen::Matrix<double, 6, 1>>(z + 6 * i) += dz;
          else Eigen::Map<Eigen::Matrix<double, 6, 1>>(z + 6 * i) = dz;
        }
      }
    });
  };
  smooth(nullptr);
  multiply(z, res);
  // Restrict r − A z to the aggregates' rigid modes.
  parallelFor(tasks, L.aggregates, 64, [&](int64_t begin, int64_t end) {
    for (int64_t a = begin; a < end; ++a) {
      Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
      for (int32_t m = L.memberStart[a]; m < L.memberStart[a + 1]; ++m) {
        const int64_t i = L.members[m];
        if (b == 3)
          sum += Eigen::Map<const Mat36>(&L.prolongation[18 * i]).transpose() *
                 (Eigen::Map<const Eigen::Vector3d>(r + 3 * i) - Eigen::Map<const Eigen::Vector3d>(res + 3 * i));
        else
          sum += Eigen::Map<const Mat6R>(&L.prolongation[36 * i]).transpose() *
                 (Eigen::Map<const Eigen::Matrix<double, 6, 1>>(r + 6 * i) -
                  Eigen::Map<const Eigen::Matrix<double, 6, 1>>(res + 6 * i));
      }
      Eigen::Map<Eigen::Matrix<double, 6, 1>>(&L.rhs[6 * a]) = sum;
    }
  });
  cycle(tasks, level + 1, L.rhs.data(), L.correction.data());
  // Prolongate the correction.
  parallelFor(tasks, nodes, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const Eigen::Map<const Eigen::Matrix<double, 6, 1>> zc(&L.correction[6 * static_cast<int64_t>(L.aggregateOf[i])]);
      if (b == 3) Eigen::Map<Eigen::Vector3d>(z + 3 * i) += Eigen::Map<const Mat36>(&L.prolongation[18 * i]) * zc;
      else Eigen::Map<Eigen::Matrix<double, 6, 1>>(z + 6 * i) += Eigen::Map<const Mat6R>(&L.prolongation[36 * i]) * zc;
    }
  });
  multiply(z, res);
  smooth(res);
}

void AggregationMultigrid::apply(TaskSystem& tasks, const double* r, double* z) { cycle(tasks, 0, r, z); }

}  // namespace vp
