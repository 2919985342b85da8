// The liquid free surface as the pressure solve sees it: the symmetric ghost-fluid Dirichlet
// condition p = 0 on the zero isosurface of the liquid level set (Gibou et al. 2002; Enright,
// Nguyen, Gibou, Fedkiw 2003).
//
// Level set convention (shared by every liquid module): phi is cell-centred, one value per
// cell in cell order, phi < 0 inside the liquid, phi >= 0 in air, a signed distance in metres.
//
// For a liquid cell c and an air neighbour nb across a face, the surface crosses the segment
// between their centres at the fraction theta = phi_c / (phi_c - phi_nb) of the way from c
// (linear interpolation of phi). Extrapolating p linearly from p_c through p = 0 at the
// crossing gives the ghost value
//     p_ghost = p_c (1 - 1/theta),   so   p_c - p_ghost = p_c / theta,
// which the operator uses in place of p_c - p_nb (the face's coupling moves to the diagonal
// as A_f / theta, keeping the operator symmetric) and the velocity update uses as the
// pressure difference across the face. Both use freeSurfaceTheta(), so the velocity is
// updated with exactly the gradient the solve balanced. A pressure that is linear in space
// (hydrostatic) is reproduced exactly when phi is linear across the face.
#pragma once

#include "gpu_kernels/pressure_update_kernels.h"

namespace vp {

// One home for the crossing, the CPU's and a device's (gpu_kernels/pressure_update_kernels.h).
using kernels::freeSurfaceTheta;
using kernels::isLiquid;
using kernels::kMinFreeSurfaceTheta;

}  // namespace vp
