#include "linalg/p_multigrid.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <Eigen/Dense>

#include "core/parallel_for.h"
#include "linalg/symmetric_pseudo_inverse.h"
#include "linalg/vector_ops.h"

namespace vp {
namespace {

using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using Vec3d = Eigen::Vector3d;

constexpr int64_t kNodeGrain = 512;
constexpr int64_t kGalerkinGrain = 32;
// Power iterations for λmax(D⁻¹A), refreshed every kLambdaRefresh updates. The Rayleigh
// quotient of the pencil (A, D) converges from below; the margin keeps the top of the
// spectrum inside the Chebyshev interval, where the smoother is a contraction.
constexpr int kPowerIterations = 10;
constexpr double kLambdaMargin = 1.1;
constexpr uint64_t kLambdaRefresh = 8;

// y = F x for a node's filter.
inline Vec3d filtered(uint8_t kind, const double* F, const Vec3d& x) {
  if (kind == 0) return x;
  if (kind == 1) return Vec3d::Zero();
  return Eigen::Map<const Mat3R>(F) * x;
}

}  // namespace

void PMultigrid::build(const BlockSparseMatrix<double>& fine, std::vector<NodeProlongation> prolongations,
                       const PMultigridSettings& settings, std::vector<BlockSparseMatrix<double>*> rediscretized) {
  settings_ = settings;
  levels_.clear();
  updates_ = 0;
  rediscretized_ = !rediscretized.empty();
  assert(!rediscretized_ || rediscretized.size() == prolongations.size());
  levels_.resize(prolongations.size() + 1);
  levels_[0].nodes = fine.blockRows;
  levels_[0].matrix = &fine;
  for (size_t l = 1; l < levels_.size(); ++l) {
    Level& L = levels_[l];
    L.P = std::move(prolongations[l - 1]);
    L.nodes = L.P.coarseNodes;
    // Restriction = Pᵀ in CSR over coarse nodes (fine nodes ascending in each row: the sums
    // have a fixed order).
    L.restrictStart.assign(static_cast<size_t>(L.nodes) + 1, 0);
    for (int32_t c : L.P.columns) L.restrictStart[c + 1]++;
    for (int32_t a = 0; a < L.nodes; ++a) L.restrictStart[a + 1] += L.restrictStart[a];
    L.restrictFine.resize(L.P.columns.size());
    L.restrictWeight.resize(L.P.columns.size());
    Array<int32_t> fill(L.restrictStart.begin(), L.restrictStart.end() - 1);
    for (int32_t i = 0; i < L.P.fineNodes; ++i)
      for (int32_t k = L.P.rowStart[i]; k < L.P.rowStart[i + 1]; ++k) {
        const int32_t slot = fill[L.P.columns[k]]++;
        L.restrictFine[slot] = i;
        L.restrictWeight[slot] = L.P.weights[k];
      }
    if (rediscretized_) {
      assert(rediscretized[l - 1]->blockRows == L.nodes);
      L.coarse = rediscretized[l - 1];
      L.matrix = L.coarse;
      continue;
    }
    // Symbolic Galerkin product: coarse a couples b when a fine block (i, j) has a ∈ P(i),
    // b ∈ P(j).
    const BlockSparseMatrix<double>& A = *levels_[l - 1].matrix;
    BlockSparseMatrix<double>& C = L.galerkin;
    C.blockRows = L.nodes;
    C.rowStart.assign(static_cast<size_t>(L.nodes) + 1, 0);
    C.columns.clear();
    Array<int32_t> mark(static_cast<size_t>(L.nodes), -1), row;
    for (int32_t a = 0; a < L.nodes; ++a) {
      row.clear();
      row.push_back(a);
      mark[a] = a;
      for (int32_t t = L.restrictStart[a]; t < L.restrictStart[a + 1]; ++t) {
        const int32_t i = L.restrictFine[t];
        for (int32_t k = A.rowStart[i]; k < A.rowStart[i + 1]; ++k) {
          const int32_t j = A.columns[k];
          for (int32_t s = L.P.rowStart[j]; s < L.P.rowStart[j + 1]; ++s) {
            const int32_t b = L.P.columns[s];
            if (mark[b] != a) mark[b] = a, row.push_back(b);
          }
        }
      }
      std::sort(row.begin(), row.end());
      C.columns.insert(C.columns.end(), row.begin(), row.end());
      C.rowStart[a + 1] = static_cast<int32_t>(C.columns.size());
    }
    C.values.assign(9 * C.columns.size(), 0.0);
    C.diagonal.resize(static_cast<size_t>(L.nodes));
    for (int32_t a = 0; a < L.nodes; ++a) C.diagonal[a] = C.find(a, a);
    L.coarse = &C;
    L.matrix = &C;
  }
  for (Level& L : levels_) {
    const size_t n3 = 3 * static_cast<size_t>(L.nodes);
    L.filters.assign(9 * static_cast<size_t>(L.nodes), 0.0);
    L.filterKind.assign(static_cast<size_t>(L.nodes), kIdentity);
    L.diagonalInverse.assign(9 * static_cast<size_t>(L.nodes), 0.0);
    for (Array<double>* v : {&L.rhs, &L.z, &L.residual, &L.direction, &L.product, &L.post, &L.smoothed}) v->assign(n3, 0.0);
  }
  coarsest_.build(*levels_.back().matrix);
}

void PMultigrid::coarseFilters(TaskSystem& tasks, int level) {
  Level& L = levels_[level];
  const Level& Fl = levels_[level - 1];
  // Galerkin: the projector onto the directions some fine reader may move in (the range of
  // Σ F_i over the fine nodes reading the coarse node): I where any reader is free, 0 where
  // all are pinned, the tangent plane where all slide on the same plane. Directions outside
  // it prolongate to zero, so dropping them loses nothing and keeps the coarse diagonal
  // blocks invertible on what remains; the product P̃ᵀAP̃ truncates each coarse function at
  // the constrained fine nodes it reaches.
  // Re-discretized: an assembled operator cannot truncate, so a coarse node may only move
  // where every reader may (the intersection of the ranges: the null space of Σ (I − F_i)).
  // Then P F_c maps into the constrained fine space, and the coarse operator is the exact
  // Galerkin operator of that smaller, conforming coarse space; for a pinned face it is the
  // coarse degree's own clamp (its control points on the face pinned).
  parallelFor(tasks, L.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
    for (int64_t a = begin; a < end; ++a) {
      Eigen::Map<Mat3R> F(&L.filters[9 * a]);
      bool decided = false;  // identity or zero, found while summing
      Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
      for (int32_t t = L.restrictStart[a]; t < L.restrictStart[a + 1] && !decided; ++t) {
        const int64_t i = L.restrictFine[t];
        const uint8_t kind = Fl.filterKind[i];
        if (rediscretized_) {
          decided = kind == kZero;
          if (kind == kGeneral) S += Eigen::Matrix3d::Identity() - Eigen::Map<const Mat3R>(&Fl.filters[9 * i]);
        } else {
          decided = kind == kIdentity;
          if (kind == kGeneral) S += Eigen::Map<const Mat3R>(&Fl.filters[9 * i]);
        }
      }
      // Union: the eigenvectors of S with a positive eigenvalue; intersection: with a zero one.
      const bool identity = rediscretized_ ? !decided && S.isZero(0.0) : decided;
      const bool zero = rediscretized_ ? decided : !decided && S.isZero(0.0);
      if (identity || zero) {
        if (identity) F.setIdentity();
        else F.setZero();
        L.filterKind[a] = identity ? kIdentity : kZero;
        continue;
      }
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
      const double cutoff = 1e-9 * std::max(eig.eigenvalues().cwiseAbs().maxCoeff(), 1e-300);
      F.setZero();
      int rank = 0;
      for (int k = 0; k < 3; ++k)
        if ((eig.eigenvalues()[k] > cutoff) != rediscretized_)
          F += eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose(), ++rank;
      L.filterKind[a] = rank == 3 ? kIdentity : rank == 0 ? kZero : kGeneral;
      if (rank == 3) F.setIdentity();
    }
  });
}

void PMultigrid::constrainRow(Level& L, int64_t a) {
  // Block (a, b) becomes F_a C_ab F_b. Filtered-out directions get a positive diagonal (σ,
  // the block's mean diagonal) so the coarsest multigrid, which inverts diagonal blocks
  // before filtering them, sees an invertible block; every cycle projects those directions
  // away, so σ never acts.
  BlockSparseMatrix<double>& C = *L.coarse;
  const bool rowFiltered = L.filterKind[a] != kIdentity;
  for (int32_t k = C.rowStart[a]; k < C.rowStart[a + 1]; ++k) {
    const int32_t b = C.columns[k];
    Eigen::Map<Mat3R> block(&C.values[9 * static_cast<int64_t>(k)]);
    if (rowFiltered) block = Eigen::Map<const Mat3R>(&L.filters[9 * a]) * block;
    if (L.filterKind[b] != kIdentity) block = block * Eigen::Map<const Mat3R>(&L.filters[9 * static_cast<int64_t>(b)]);
  }
  if (rowFiltered) {
    Eigen::Map<Mat3R> diagonal(&C.values[9 * static_cast<int64_t>(C.diagonal[a])]);
    const double trace = diagonal.trace();
    const double sigma = trace > 0.0 ? trace / 3.0 : 1.0;
    diagonal += sigma * (Mat3R::Identity() - Eigen::Map<const Mat3R>(&L.filters[9 * a]));
  }
}

void PMultigrid::coarseOperator(TaskSystem& tasks, int level) {
  Level& L = levels_[level];
  if (rediscretized_) {
    // The caller's operator of this degree, restricted to the constrained coarse space.
    parallelFor(tasks, L.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
      for (int64_t a = begin; a < end; ++a) constrainRow(L, a);
    });
    return;
  }
  const Level& Fl = levels_[level - 1];
  const BlockSparseMatrix<double>& A = *Fl.matrix;
  BlockSparseMatrix<double>& C = L.galerkin;
  // C_ab = F_a Σ w_ia w_jb F_i A_ij F_j F_b, one coarse row per task (no races, fixed order).
  parallelFor(tasks, L.nodes, kGalerkinGrain, [&](int64_t begin, int64_t end) {
    // Coarse column -> block index of the current row; every entry is reset to -1 after its
    // row, so a worker's scratch can be reused across chunks and updates without clearing.
    thread_local Array<int32_t> slot;
    if (slot.size() < static_cast<size_t>(L.nodes)) slot.assign(static_cast<size_t>(L.nodes), -1);
    for (int64_t a = begin; a < end; ++a) {
      for (int32_t k = C.rowStart[a]; k < C.rowStart[a + 1]; ++k) {
        slot[C.columns[k]] = k;
        std::fill_n(&C.values[9 * static_cast<int64_t>(k)], 9, 0.0);
      }
      for (int32_t t = L.restrictStart[a]; t < L.restrictStart[a + 1]; ++t) {
        const int32_t i = L.restrictFine[t];
        const uint8_t ki = Fl.filterKind[i];
        if (ki == kZero) continue;
        const double wi = L.restrictWeight[t];
        for (int32_t k = A.rowStart[i]; k < A.rowStart[i + 1]; ++k) {
          const int32_t j = A.columns[k];
          const uint8_t kj = Fl.filterKind[j];
          if (kj == kZero) continue;
          Mat3R B = Eigen::Map<const Mat3R>(&A.values[9 * static_cast<int64_t>(k)]);
          if (ki == kGeneral) B = Eigen::Map<const Mat3R>(&Fl.filters[9 * static_cast<int64_t>(i)]) * B;
          if (kj == kGeneral) B = B * Eigen::Map<const Mat3R>(&Fl.filters[9 * static_cast<int64_t>(j)]);
          for (int32_t s = L.P.rowStart[j]; s < L.P.rowStart[j + 1]; ++s)
            Eigen::Map<Mat3R>(&C.values[9 * static_cast<int64_t>(slot[L.P.columns[s]])]) += (wi * L.P.weights[s]) * B;
        }
      }
      for (int32_t k = C.rowStart[a]; k < C.rowStart[a + 1]; ++k) slot[C.columns[k]] = -1;
      constrainRow(L, a);
    }
  });
}

void PMultigrid::estimateLambdaMax(TaskSystem& tasks, Level& L) {
  // Power iteration on D⁺A from a fixed vector; λ from the Rayleigh quotient vᵀAv / vᵀDv.
  const int64_t n = 3 * static_cast<int64_t>(L.nodes);
  double* v = L.direction.data();
  double* w = L.product.data();
  double* dv = L.post.data();
  for (int64_t i = 0; i < n; ++i) v[i] = 1.0 + 0.01 * static_cast<double>(i % 7);
  double lambda = 0.0;
  for (int it = 0; it < kPowerIterations; ++it) {
    parallelFor(tasks, L.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        Eigen::Map<Vec3d> vi(v + 3 * i);
        vi = filtered(L.filterKind[i], &L.filters[9 * i], vi);
        Eigen::Map<Vec3d>(dv + 3 * i) =
            Eigen::Map<const Mat3R>(&L.matrix->values[9 * static_cast<int64_t>(L.matrix->diagonal[i])]) * vi;
      }
    });
    L.matrix->multiply(tasks, v, w);
    const double vAv = vec::dot(tasks, n, v, w), vDv = vec::dot(tasks, n, v, dv);
    if (!(vDv > 0.0)) break;
    lambda = std::max(lambda, vAv / vDv);
    parallelFor(tasks, L.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i)
        Eigen::Map<Vec3d>(v + 3 * i) = Eigen::Map<const Mat3R>(&L.diagonalInverse[9 * i]) * Eigen::Map<const Vec3d>(w + 3 * i);
    });
    const double norm = std::sqrt(vec::dot(tasks, n, v, v));
    if (!(norm > 0.0)) break;
    for (int64_t i = 0; i < n; ++i) v[i] /= norm;
  }
  L.lambdaMax = kLambdaMargin * std::max(lambda, 1e-300);
}

void PMultigrid::update(TaskSystem& tasks, const BlockSparseMatrix<double>& fine, const double* positions,
                        const double* filters) {
  Level& top = levels_[0];
  top.matrix = &fine;
  parallelFor(tasks, top.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      Eigen::Map<Mat3R> F(&top.filters[9 * i]);
      if (filters) F = Eigen::Map<const Mat3R>(filters + 9 * i);
      else F.setIdentity();
      top.filterKind[i] = F.isIdentity(0.0) ? kIdentity : F.isZero(0.0) ? kZero : kGeneral;
    }
  });
  for (int l = 1; l < levelCount(); ++l) {
    coarseFilters(tasks, l);
    coarseOperator(tasks, l);
  }
  const bool refresh = updates_++ % kLambdaRefresh == 0;
  for (int l = 0; l < levelCount(); ++l) {
    Level& L = levels_[l];
    // Smoother diagonal F D⁺ F (D of a coarse level can be singular where a fine constraint
    // removed a direction: the pseudo-inverse gives it no correction).
    parallelFor(tasks, L.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        Eigen::Map<Mat3R> out(&L.diagonalInverse[9 * i]);
        if (L.filterKind[i] == kZero) {
          out.setZero();
          continue;
        }
        Mat3R inv = symmetricPseudoInverse<3>(
            Mat3R(Eigen::Map<const Mat3R>(&L.matrix->values[9 * static_cast<int64_t>(L.matrix->diagonal[i])])));
        if (L.filterKind[i] == kGeneral) {
          const Eigen::Map<const Mat3R> F(&L.filters[9 * i]);
          inv = F * inv * F;
        }
        out = inv;
      }
    });
    if (l + 1 < levelCount() && refresh) estimateLambdaMax(tasks, L);
  }
  coarsest_.update(tasks, *levels_.back().matrix, positions, levels_.back().filters.data());
}

void PMultigrid::smooth(TaskSystem& tasks, Level& L, const double* rhs, double* out, bool wantResidual) {
  // Chebyshev iteration for D⁺A on [a, b] from a zero start (Saad, Iterative Methods, alg.
  // 12.1); damped Jacobi is the same loop with ρ = 0 and a fixed step ω.
  const int64_t n = 3 * static_cast<int64_t>(L.nodes);
  const bool chebyshev = settings_.smoother == PMultigridSmoother::Chebyshev;
  const double b = L.lambdaMax, a = b / settings_.chebyshevRange;
  const double theta = 0.5 * (b + a), delta = 0.5 * (b - a), sigma = theta / delta;
  double rho = 1.0 / sigma;
  double keep = 0.0, step = chebyshev ? 1.0 / theta : 4.0 / (3.0 * b);
  double* res = L.residual.data();
  double* d = L.direction.data();
  double* Ad = L.product.data();
  const int sweeps = std::max(settings_.sweeps, 1);
  for (int k = 0; k < sweeps; ++k) {
    const double* source = k == 0 ? rhs : res;
    parallelFor(tasks, L.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        const Vec3d di = keep * Eigen::Map<const Vec3d>(d + 3 * i) +
                         step * (Eigen::Map<const Mat3R>(&L.diagonalInverse[9 * i]) * Eigen::Map<const Vec3d>(source + 3 * i));
        Eigen::Map<Vec3d>(d + 3 * i) = di;
        if (k == 0) Eigen::Map<Vec3d>(out + 3 * i) = di;
        else Eigen::Map<Vec3d>(out + 3 * i) += di;
      }
    });
    if (k + 1 == sweeps && !wantResidual) break;
    L.matrix->multiply(tasks, d, Ad);
    if (k == 0) {
      parallelFor(tasks, n, vec::kGrain, [&](int64_t begin, int64_t end) {
        for (int64_t i = begin; i < end; ++i) res[i] = rhs[i] - Ad[i];
      });
    } else {
      vec::axpy(tasks, n, -1.0, Ad, res);
    }
    if (chebyshev) {
      const double rhoNext = 1.0 / (2.0 * sigma - rho);
      keep = rhoNext * rho;
      step = 2.0 * rhoNext / delta;
      rho = rhoNext;
    }
  }
}

void PMultigrid::coarsestSolve(TaskSystem& tasks, const double* r, double* z) {
  // c V-cycles of a symmetric B as a stationary iteration: Σ_j (I − BA)^j B is symmetric too.
  Level& L = levels_.back();
  const int64_t n = 3 * static_cast<int64_t>(L.nodes);
  coarsest_.apply(tasks, r, z);
  for (int c = 1; c < settings_.coarseCycles; ++c) {
    L.matrix->multiply(tasks, z, L.product.data());
    parallelFor(tasks, n, vec::kGrain, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) L.residual[i] = r[i] - L.product[i];
    });
    coarsest_.apply(tasks, L.residual.data(), L.direction.data());
    vec::axpy(tasks, n, 1.0, L.direction.data(), z);
  }
}

void PMultigrid::cycle(TaskSystem& tasks, int level, const double* r, double* z) {
  if (level + 1 == levelCount()) return coarsestSolve(tasks, r, z);
  Level& L = levels_[level];
  Level& C = levels_[level + 1];
  const int64_t n = 3 * static_cast<int64_t>(L.nodes);
  smooth(tasks, L, r, z, true);
  // Restrict the residual: rc_a = F_a Σ w_ia F_i res_i.
  parallelFor(tasks, C.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
    for (int64_t a = begin; a < end; ++a) {
      Vec3d sum = Vec3d::Zero();
      for (int32_t t = C.restrictStart[a]; t < C.restrictStart[a + 1]; ++t) {
        const int64_t i = C.restrictFine[t];
        sum += C.restrictWeight[t] * filtered(L.filterKind[i], &L.filters[9 * i], Eigen::Map<const Vec3d>(&L.residual[3 * i]));
      }
      Eigen::Map<Vec3d>(&C.rhs[3 * a]) = filtered(C.filterKind[a], &C.filters[9 * a], sum);
    }
  });
  cycle(tasks, level + 1, C.rhs.data(), C.z.data());
  // Prolongate: z_i += F_i Σ w_ia F_a zc_a.
  parallelFor(tasks, C.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
    for (int64_t a = begin; a < end; ++a) {
      Eigen::Map<Vec3d> zc(&C.z[3 * a]);
      zc = filtered(C.filterKind[a], &C.filters[9 * a], zc);
    }
  });
  parallelFor(tasks, L.nodes, kNodeGrain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      Vec3d sum = Vec3d::Zero();
      for (int32_t s = C.P.rowStart[i]; s < C.P.rowStart[i + 1]; ++s)
        sum += C.P.weights[s] * Eigen::Map<const Vec3d>(&C.z[3 * static_cast<int64_t>(C.P.columns[s])]);
      Eigen::Map<Vec3d>(z + 3 * i) += filtered(L.filterKind[i], &L.filters[9 * i], sum);
    }
  });
  // Post-smoothing with the same polynomial: z += S (r − A z).
  L.matrix->multiply(tasks, z, L.product.data());
  double* post = L.post.data();
  parallelFor(tasks, n, vec::kGrain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) post[i] = r[i] - L.product[i];
  });
  smooth(tasks, L, post, L.smoothed.data(), false);
  vec::axpy(tasks, n, 1.0, L.smoothed.data(), z);
}

void PMultigrid::apply(TaskSystem& tasks, const double* r, double* z) { cycle(tasks, 0, r, z); }

}  // namespace vp
