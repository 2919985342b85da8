#include "deform/node_constraints.h"

#include <Eigen/Core>
#include <algorithm>

#include "core/math_types.h"
#include "core/parallel_for.h"
#include "gpu_kernels/constraint_kernels.h"

namespace vp {

void NodeConstraints::resize(int32_t nodeCount) {
  kind.assign(static_cast<size_t>(nodeCount), kFree);
  normal.assign(3 * static_cast<size_t>(nodeCount), 0.0);
}

void NodeConstraints::clear() { std::fill(kind.begin(), kind.end(), kFree); }

void NodeConstraints::filter(TaskSystem& tasks, double* vec) const {
  parallelFor(tasks, static_cast<int64_t>(kind.size()), 1024, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) kernels::filterNode(i, kind.data(), normal.data(), vec);
  });
}

void NodeConstraints::projectors(TaskSystem& tasks, double* out) const {
  parallelFor(tasks, static_cast<int64_t>(kind.size()), 1024, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> F(&out[9 * i]);
      if (kind[i] == kFixed) F.setZero();
      else if (kind[i] == kContact) F = Mat3::Identity() - Eigen::Map<const Vec3>(&normal[3 * i]) *
                                                          Eigen::Map<const Vec3>(&normal[3 * i]).transpose();
      else F.setIdentity();
    }
  });
}

}  // namespace vp
