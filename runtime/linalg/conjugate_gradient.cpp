#include "linalg/conjugate_gradient.h"

#include <cmath>

#include "linalg/vector_ops.h"

namespace vp {

CgResult solveConjugateGradient(TaskSystem& tasks, const LinearSystem& sys, const double* b, double* x,
                                const CgSettings& settings, const Deadline& deadline, CgWorkspace& w) {
  const int64_t n = sys.size;
  for (Array<double>* v : {&w.r, &w.z, &w.p, &w.q}) v->resize(static_cast<size_t>(n));
  double* r = w.r.data();
  double* z = w.z.data();
  double* p = w.p.data();
  double* q = w.q.data();
  auto filter = [&](double* v) {
    if (sys.filter) sys.filter(v);
  };
  auto precondition = [&](const double* in, double* out) {
    if (sys.precondition) sys.precondition(in, out);
    else vec::copy(tasks, n, in, out);
  };

  CgResult result;
  // |filtered b| is the scale the tolerance is relative to.
  vec::copy(tasks, n, b, z);
  filter(z);
  const double bNorm = std::sqrt(vec::dot(tasks, n, z, z));

  sys.apply(x, q);
  vec::copy(tasks, n, b, r);
  vec::axpy(tasks, n, -1.0, q, r);
  filter(r);
  double rNorm = std::sqrt(vec::dot(tasks, n, r, r));
  if (bNorm == 0.0) {
    // Nothing drives the system: x = 0 in the free subspace is the exact answer.
    result.relativeResidual = rNorm;
    result.converged = rNorm == 0.0;
    if (!result.converged) {
      vec::copy(tasks, n, x, z);
      filter(z);
      vec::axpy(tasks, n, -1.0, z, x);
      result.converged = true;
      result.relativeResidual = 0.0;
    }
    return result;
  }
  result.relativeResidual = rNorm / bNorm;
  if (result.relativeResidual <= settings.relativeTolerance) {
    result.converged = true;
    return result;
  }

  precondition(r, z);
  filter(z);
  vec::copy(tasks, n, z, p);
  double rz = vec::dot(tasks, n, r, z);
  for (int it = 0; it < settings.maxIterations; ++it) {
    if (it >= settings.minIterations && deadline.expired()) {
      result.budgetCut = true;
      break;
    }
    sys.apply(p, q);
    filter(q);
    const double pq = vec::dot(tasks, n, p, q);
    if (!(pq > 0.0)) break;  // A not positive on p: numerically converged or broken input
    const double alpha = rz / pq;
    rNorm = std::sqrt(vec::cgStep(tasks, n, alpha, p, q, x, r));
    result.iterations = it + 1;
    result.relativeResidual = rNorm / bNorm;
    if (result.relativeResidual <= settings.relativeTolerance) {
      result.converged = true;
      break;
    }
    precondition(r, z);
    filter(z);
    const double rzNext = vec::dot(tasks, n, r, z);
    vec::xpby(tasks, n, z, rzNext / rz, p);
    rz = rzNext;
  }
  return result;
}

}  // namespace vp
