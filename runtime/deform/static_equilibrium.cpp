#include "deform/static_equilibrium.h"

#include <algorithm>
#include <cmath>

namespace vp {
namespace {

// The first pseudo-time step, and the largest (where M/h² is negligible beside any stiffness
// a deformable may have, so the step is Newton's). Chosen for metre-scale bodies of
// kilopascal-to-gigapascal stiffness; the continuation adapts h from there.
constexpr double kFirstPseudoStep = 0.05;
constexpr double kMaxPseudoStep = 1e6;
constexpr double kMinPseudoStep = 1e-6;
// Backtracking halvings before a pseudo-step is rejected, and the sufficient decrease (Armijo)
// factor on the potential.
constexpr int kLineSearchHalvings = 6;
constexpr double kSufficientDecrease = 1e-4;

// A pseudo-step's linear solve may take kSolverCapPerUnknown CG iterations per unknown (CG's
// finite-termination bound, stretched by rounding), at least the desc's cap: as h grows the
// system becomes K alone, which on slender linear elements needs far more than a frame's cap.
constexpr int64_t kSolverCapPerUnknown = 10;

int32_t pseudoStepSolverCap(const DeformableBody& body) {
  const int64_t unknowns = 3 * static_cast<int64_t>(body.nodeCount());
  const int64_t cap = std::min<int64_t>(kSolverCapPerUnknown * unknowns, DeformableSolverSettings::kMaxSolverIterations);
  return static_cast<int32_t>(std::max<int64_t>(cap, body.desc().solver.maxIterations));
}

struct Forces {
  Array<double> load;     // M g + f_ext per node
  Array<uint8_t> held;    // pinned or attached
  double scale = 0.0;     // ‖load‖, the residual's reference
};

// What the line search and the convergence test need at the body's current positions.
struct Evaluation {
  Array<double> force;    // f(x) + load per node (minus the potential's gradient)
  double potential = 0.0; // elastic energy − load · (x − origin)
  double residual = 0.0;  // ‖force‖ over what no constraint carries (see the header)
};

double residualNorm(const DeformableBody& body, const Forces& forces, Array<double> f) {
  for (int32_t i = 0; i < body.nodeCount(); ++i)
    if (forces.held[i]) f[3 * i] = f[3 * i + 1] = f[3 * i + 2] = 0.0;
  for (const NodeContact& c : body.contacts()) {
    if (forces.held[c.node]) continue;
    Vec3 r(f[3 * c.node], f[3 * c.node + 1], f[3 * c.node + 2]);
    const double into = -r.dot(c.normal);
    if (into <= 0.0) continue;  // pulls away from the collider: nothing carries it
    Vec3 tangential = r + into * c.normal;
    const double t = tangential.norm();
    const double carried = std::min(t, c.friction * into);
    if (t > 0.0) tangential *= (t - carried) / t;
    for (int k = 0; k < 3; ++k) f[3 * c.node + k] = tangential[k];
  }
  double sum = 0.0;
  for (double v : f) sum += v * v;
  return std::sqrt(sum);
}

Evaluation evaluate(DeformableBody& body, TaskSystem& tasks, const Forces& forces, const Array<double>& origin) {
  Evaluation e;
  body.elasticForces(tasks, &e.force);
  e.potential = body.elasticEnergy(tasks);
  const Array<double>& x = body.positions();
  for (size_t i = 0; i < e.force.size(); ++i) {
    e.force[i] += forces.load[i];
    e.potential -= forces.load[i] * (x[i] - origin[i]);
  }
  e.residual = residualNorm(body, forces, e.force);
  return e;
}

Forces externalForces(const DeformableBody& body, const DeformableStepInput& input, const Array<double>& pending) {
  Forces forces;
  const int32_t n = body.nodeCount();
  forces.load.resize(3 * static_cast<size_t>(n));
  double sum = 0.0;
  for (int32_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = body.nodeMasses()[i] * input.gravity[k] + pending[3 * i + k];
      forces.load[3 * i + k] = v;
      sum += v * v;
    }
  forces.scale = std::sqrt(sum);
  body.heldNodes(&forces.held);
  return forces;
}

void reapply(DeformableBody& body, const Array<double>& pending) {
  for (int32_t i = 0; i < body.nodeCount(); ++i) {
    const Vec3 f(pending[3 * i], pending[3 * i + 1], pending[3 * i + 2]);
    if (f != Vec3::Zero()) body.applyForce(i, f);
  }
}

void zeroVelocities(DeformableBody& body) {
  const Array<double> zero(body.velocities().size(), 0.0);
  body.setVelocities(zero.data(), static_cast<int64_t>(zero.size()));
}

// Whether a surface node at the body's positions lies inside a collider.
bool penetrates(const DeformableBody& body, const DeformableStepInput& input) {
  const Array<double> rest(body.velocities().size(), 0.0);
  Array<NodeContact> inside;
  findNodeContacts(body.positions(), rest, body.surfaceNodes(), input.colliders, input.dt, 0.0, 0.0, &inside);
  return !inside.empty();
}

// One backward-Euler step from rest. When it ends with nodes inside a collider (contacts are
// found along the motion, and from rest there is none), it is redone from its start with its
// own displacement as the contacts' lookahead, so those nodes land on the surface instead.
void pseudoStep(DeformableBody& body, const DeformableStepInput& input, const Array<double>& pending,
                bool* forcesPending, ActorStats* stats) {
  if (!*forcesPending) reapply(body, pending);
  DeformableState start = body.saveState();  // with the pending forces
  body.step(input, stats);
  *forcesPending = false;
  if (stats->diverged || input.colliders.empty() || !penetrates(body, input)) {
    zeroVelocities(body);
    return;
  }
  const Array<double> lookahead = body.velocities();
  body.restoreState(std::move(start));
  DeformableStepInput caught = input;
  caught.contactLookahead = &lookahead;
  *stats = ActorStats{};
  body.step(caught, stats);
  zeroVelocities(body);
}

void moveTo(DeformableBody& body, const Array<double>& x) {
  body.setPositions(x.data(), static_cast<int64_t>(x.size()));
}

// Armijo backtracking along the pseudo-step's displacement d, from `start` (evaluated as `at`)
// to where the step left the body: the slope at the start is −(f + load) · d. Near the solution
// the potential's changes sink below its rounding, so a falling residual also accepts. Leaves
// the body at the accepted point (*next, *alpha) and returns true, or returns false.
bool lineSearch(DeformableBody& body, TaskSystem& tasks, const Forces& forces, const Array<double>& origin,
                const Array<double>& start, const Evaluation& at, Evaluation* next, double* alpha) {
  const Array<double> full(body.positions().begin(), body.positions().end());
  double slope = 0.0;
  for (size_t i = 0; i < full.size(); ++i) slope -= at.force[i] * (full[i] - start[i]);
  Array<double> x(start.size());
  for (int halving = 0; halving <= kLineSearchHalvings; ++halving) {
    *alpha = std::ldexp(1.0, -halving);
    if (halving > 0) {
      for (size_t i = 0; i < x.size(); ++i) x[i] = start[i] + *alpha * (full[i] - start[i]);
      moveTo(body, x);
    }
    *next = evaluate(body, tasks, forces, origin);
    if (std::isfinite(next->potential) && std::isfinite(next->residual) &&
        (next->potential <= at.potential + kSufficientDecrease * *alpha * std::min(slope, 0.0) ||
         next->residual <= (1.0 - kSufficientDecrease * *alpha) * at.residual))
      return true;
  }
  return false;
}

// The continuation from the body's state at rest; returns how far it got.
StaticSolveResult continueToRest(DeformableBody& body, const DeformableStepInput& input, const Array<double>& pending,
                                 const Array<double>& origin, int32_t maxIterations, double tolerance) {
  TaskSystem& tasks = *input.tasks;
  const Forces forces = externalForces(body, input, pending);
  bool forcesPending = true;  // a step consumes the body's pending forces
  zeroVelocities(body);
  Evaluation at = evaluate(body, tasks, forces, origin);
  const double reference = forces.scale > 0.0 ? forces.scale : at.residual;
  auto relative = [&](double r) { return reference > 0.0 ? r / reference : 0.0; };
  StaticSolveResult out;
  out.residual = relative(at.residual);
  out.converged = out.residual <= tolerance;
  double h = kFirstPseudoStep;
  Array<double> start;
  while (!out.converged && out.iterations < maxIterations && h >= kMinPseudoStep) {
    ++out.iterations;
    start.assign(body.positions().begin(), body.positions().end());
    DeformableStepInput pseudo = input;
    pseudo.dt = h;
    pseudo.solverMaxIterations = pseudoStepSolverCap(body);
    ActorStats stats;
    pseudoStep(body, pseudo, pending, &forcesPending, &stats);
    Evaluation next;
    double alpha = 0.0;
    const bool accepted = !stats.diverged && lineSearch(body, tasks, forces, origin, start, at, &next, &alpha);
    if (!accepted) {
      moveTo(body, start);
      at = evaluate(body, tasks, forces, origin);
      h *= 0.25;
      continue;
    }
    // A full step grows h by the residual's fall (at least doubling); a shortened one keeps it.
    if (alpha == 1.0)
      h = std::min(kMaxPseudoStep, h * std::max(2.0, at.residual / std::max(next.residual, 1e-300)));
    at = std::move(next);
    out.residual = relative(at.residual);
    out.converged = out.residual <= tolerance;
  }
  // At rest where it stands, with the host's forces still pending for the next step.
  if (!forcesPending) reapply(body, pending);
  body.updateRenderMesh(tasks);
  return out;
}

}  // namespace

Status solveStaticEquilibrium(DeformableBody& body, const DeformableStepInput& input, int32_t maxIterations,
                              double tolerance, StaticSolveResult* result) {
  if (maxIterations < 1 || maxIterations > kMaxStaticIterations)
    return fail(Status::InvalidArgument, "maxIterations = %d: must be in [1, %d]", maxIterations,
                kMaxStaticIterations);
  if (!std::isfinite(tolerance) || tolerance <= 0.0 || tolerance >= 1.0)
    return fail(Status::InvalidArgument, "tolerance = %g: must be finite and in (0, 1)", tolerance);
  // The state to go back to when the solve does not converge or runs out of memory.
  DeformableState before = body.saveState();
  StaticSolveResult out;
  try {
    out = continueToRest(body, input, before.externalForce, before.x, maxIterations, tolerance);
  } catch (const std::bad_alloc&) {
    body.restoreState(std::move(before));
    return fail(Status::OutOfMemory, "static solve: out of memory (the deformable is unchanged)");
  }
  if (result) *result = out;
  if (out.converged) return Status::Ok;
  body.restoreState(std::move(before));
  return fail(Status::NotConverged,
              "static solve: relative residual %g after %d iterations, above tolerance = %g (the deformable is "
              "unchanged)",
              out.residual, out.iterations, tolerance);
}

}  // namespace vp
