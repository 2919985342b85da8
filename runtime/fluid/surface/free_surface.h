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

namespace vp {

// theta is clamped below at this value. As theta -> 0 the surface reaches c's centre, the
// diagonal term A_f / theta grows without bound and the velocity update multiplies the
// solver's error in p_c by 1/theta. At 1e-3 the diagonal stays within three orders of the
// ordinary entries (MIC(0) and CG cope: the row becomes nearly Dirichlet, which they handle
// well) and the error the clamp introduces is in a cell whose pressure is itself
// O(theta * rho g h), i.e. below 1e-3 of the hydrostatic jump over one cell.
constexpr double kMinFreeSurfaceTheta = 1e-3;

inline bool isLiquid(double phi) { return phi < 0.0; }

// phiLiquid < 0 <= phiAir.
inline double freeSurfaceTheta(double phiLiquid, double phiAir) {
  const double theta = phiLiquid / (phiLiquid - phiAir);
  return theta > kMinFreeSurfaceTheta ? theta : kMinFreeSurfaceTheta;
}

}  // namespace vp
