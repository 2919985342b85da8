#include "linalg/conjugate_gradient.h"

#include <cmath>
#include <limits>

#include "linalg/vector_ops.h"

namespace vp {

ConjugateGradientRun::ConjugateGradientRun(TaskSystem& tasks, const LinearSystem& system, const double* b, double* x,
                                           const CgSettings& settings, CgWorkspace& work)
    : tasks_(tasks), system_(system), b_(b), x_(x), settings_(settings), work_(work) {}

void ConjugateGradientRun::filter(double* v) {
  if (system_.filter) system_.filter(v);
}

void ConjugateGradientRun::precondition(const double* in, double* out) {
  if (system_.precondition) system_.precondition(in, out);
  else vec::copy(tasks_, system_.size, in, out);
}

bool ConjugateGradientRun::start() {
  const int64_t n = system_.size;
  CgWorkspace& w = work_;
  for (Array<double>* v : {&w.r, &w.z, &w.p, &w.q}) v->resize(static_cast<size_t>(n));
  double* r = w.r.data();
  double* z = w.z.data();
  double* p = w.p.data();
  double* q = w.q.data();
  finished_ = true;
  // |filtered b| is the scale the tolerance is relative to.
  vec::copy(tasks_, n, b_, z);
  filter(z);
  bNorm_ = std::sqrt(vec::dot(tasks_, n, z, z));

  system_.apply(x_, q);
  vec::copy(tasks_, n, b_, r);
  vec::axpy(tasks_, n, -1.0, q, r);
  filter(r);
  const double rNorm = std::sqrt(vec::dot(tasks_, n, r, r));
  if (bNorm_ == 0.0) {
    // Nothing drives the system: x = 0 in the free subspace is the exact answer.
    result_.relativeResidual = rNorm;
    result_.converged = rNorm == 0.0;
    if (!result_.converged) {
      vec::copy(tasks_, n, x_, z);
      filter(z);
      vec::axpy(tasks_, n, -1.0, z, x_);
      result_.converged = true;
      result_.relativeResidual = 0.0;
    }
    return true;
  }
  result_.relativeResidual = rNorm / bNorm_;
  if (result_.relativeResidual <= settings_.relativeTolerance) {
    result_.converged = true;
    return true;
  }
  if (settings_.maxIterations <= 0) return true;
  precondition(r, z);
  filter(z);
  vec::copy(tasks_, n, z, p);
  rz_ = vec::dot(tasks_, n, r, z);
  finished_ = false;
  return false;
}

bool ConjugateGradientRun::iterate() {
  if (finished_) return true;
  const int64_t n = system_.size;
  double* r = work_.r.data();
  double* z = work_.z.data();
  double* p = work_.p.data();
  double* q = work_.q.data();
  finished_ = true;
  system_.apply(p, q);
  filter(q);
  const double pq = vec::dot(tasks_, n, p, q);
  if (!(pq > 0.0)) return true;  // A not positive on p: numerically converged or broken input
  const double alpha = rz_ / pq;
  const double rNorm = std::sqrt(vec::cgStep(tasks_, n, alpha, p, q, x_, r));
  ++result_.iterations;
  result_.relativeResidual = rNorm / bNorm_;
  if (result_.relativeResidual <= settings_.relativeTolerance) {
    result_.converged = true;
    return true;
  }
  if (result_.iterations >= settings_.maxIterations) return true;
  precondition(r, z);
  filter(z);
  const double rzNext = vec::dot(tasks_, n, r, z);
  vec::xpby(tasks_, n, z, rzNext / rz_, p);
  rz_ = rzNext;
  finished_ = false;
  return false;
}

CgResult solveConjugateGradient(TaskSystem& tasks, const LinearSystem& system, const double* b, double* x,
                                const CgSettings& settings, const Deadline& deadline, CgWorkspace& work,
                                double floorTolerance, const Deadline& floorDeadline) {
  ConjugateGradientRun run(tasks, system, b, x, settings, work);
  if (run.start()) return run.result();
  while (!run.finished()) {
    const CgResult& now = run.result();
    if (now.iterations >= settings.minIterations && deadline.expired() &&
        (now.relativeResidual <= floorTolerance || floorDeadline.expired())) {
      CgResult result = now;
      result.budgetCut = true;
      return result;
    }
    run.iterate();
  }
  return run.result();
}

CgResult solveConjugateGradient(TaskSystem& tasks, const LinearSystem& system, const double* b, double* x,
                                const CgSettings& settings, const Deadline& deadline, CgWorkspace& work) {
  return solveConjugateGradient(tasks, system, b, x, settings, deadline, work,
                                std::numeric_limits<double>::infinity(), deadline);
}

}  // namespace vp
