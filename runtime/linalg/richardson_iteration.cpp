#include "linalg/richardson_iteration.h"

#include <cmath>

#include "linalg/vector_ops.h"

namespace vp {

CgResult solveRichardson(TaskSystem& tasks, const LinearSystem& sys, const double* b, double* x,
                         const CgSettings& settings, const Deadline& deadline, CgWorkspace& w) {
  const int64_t n = sys.size;
  for (Array<double>* v : {&w.r, &w.z, &w.q}) v->resize(static_cast<size_t>(n));
  double* r = w.r.data();
  double* z = w.z.data();
  double* q = w.q.data();
  auto filter = [&](double* v) {
    if (sys.filter) sys.filter(v);
  };
  CgResult result;
  vec::copy(tasks, n, b, z);
  filter(z);
  const double bNorm = std::sqrt(vec::dot(tasks, n, z, z));
  for (int it = 0;; ++it) {
    sys.apply(x, q);
    vec::copy(tasks, n, b, r);
    vec::axpy(tasks, n, -1.0, q, r);
    filter(r);
    const double rNorm = std::sqrt(vec::dot(tasks, n, r, r));
    result.relativeResidual = bNorm > 0.0 ? rNorm / bNorm : rNorm;
    if (result.relativeResidual <= settings.relativeTolerance || (bNorm == 0.0 && rNorm == 0.0)) {
      result.converged = true;
      break;
    }
    if (!std::isfinite(rNorm) || it == settings.maxIterations) break;
    if (deadline.expired()) {
      result.budgetCut = true;
      break;
    }
    if (sys.precondition) sys.precondition(r, z);
    else vec::copy(tasks, n, r, z);
    filter(z);
    vec::axpy(tasks, n, 1.0, z, x);
    result.iterations = it + 1;
  }
  return result;
}

}  // namespace vp
