// Preconditioned Richardson iteration x += B (b − A x): a multigrid cycle used as a
// solver on its own rather than inside CG. Same contract as solveConjugateGradient (budget,
// filter, tolerance on |r| / |filtered b|, best iterate kept), so callers can swap the two.
// It converges when the cycle's error propagation I − BA is a contraction (a working
// multigrid); CG around the same B is never slower in iterations, which is why the actor
// uses CG and this exists to measure the cycle itself.
#pragma once

#include "linalg/conjugate_gradient.h"

namespace vp {

CgResult solveRichardson(TaskSystem& tasks, const LinearSystem& system, const double* b, double* x,
                         const CgSettings& settings, const Deadline& deadline, CgWorkspace& work);

}  // namespace vp
