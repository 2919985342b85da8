// A deformable's static equilibrium: the positions where the corotated elastic forces balance
// gravity and the pending applied forces, with pinned and attached nodes held and contacts
// against the colliders in `input.colliders` (as they stand: nothing else moves meanwhile).
//
// Method: pseudo-transient continuation (Kelley & Keyes 1998) on the body's own implicit step.
// With the velocity zeroed, one backward-Euler step of length h solves
//   (M/h² + D/h + K(x)) Δx = f(x) + M g + f_ext,
// a Newton step on the corotated equilibrium regularized by M/h² (K(x) is the corotated
// stiffness at x, the rotations frozen), with the step's own contacts, pins, attachments and
// linear solvers (p-multigrid for degree 2 and 3). Each step is globalized by a backtracking
// (Armijo) line search along Δx on the potential Π(x) = E_elastic(x) − (M g + f_ext) · x; h
// grows as the residual falls (switched evolution relaxation: h ← h · r_prev / r, at least
// doubling) until M/h² no longer matters, so the last iterations are Newton's. A step whose
// line search fails is rejected and h shrinks. A body that starts above the ground descends
// in such steps and meets it where a step's contacts catch it.
//
// Residual: the unbalanced force f(x) + M g + f_ext over the free nodes. At a contact node the
// part that pushes into the collider is carried by the contact, and tangentially up to the
// friction coefficient times that normal part; pinned and attached nodes carry everything.
// Converged when ‖residual‖ <= tolerance · ‖M g + f_ext‖ (or, with neither gravity nor applied
// forces, tolerance times the residual at the start).
#pragma once

#include <cstdint>

#include "core/status.h"
#include "deform/deformable_body.h"

namespace vp {

struct StaticSolveResult {
  int32_t iterations = 0;   // pseudo-time steps taken (accepted and rejected)
  double residual = 0.0;    // relative residual reached (see above)
  bool converged = false;
};

// maxIterations in [1, kMaxStaticIterations], tolerance finite in (0, 1). On success the body
// rests at the equilibrium with zero velocity and its pending forces still pending (the solve
// is not a step). Not converged within maxIterations: Status::NotConverged, the body back as it
// was, *result says how far it got; out of memory: Status::OutOfMemory, the body back as it was.
// input.dt is ignored; input.deadline should be unlimited.
constexpr int32_t kMaxStaticIterations = 10000;
Status solveStaticEquilibrium(DeformableBody& body, const DeformableStepInput& input, int32_t maxIterations,
                              double tolerance, StaticSolveResult* result);

}  // namespace vp
