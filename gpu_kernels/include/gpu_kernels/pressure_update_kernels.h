// Kernel bodies of the pressure projection's last pass (runtime/fluid/pressure/
// pressure_projection.h): one face's velocity u -= dt / (rho h) (p_high - p_low), and the
// liquid's free-surface crossing (runtime/fluid/surface/free_surface.h) both the update and the
// operator's build read.
//
// Faces and cells are indices into plain arrays of a MAC grid (layouts as in
// runtime/fluid/mac_grid.h). Each face is written once, from the pressure and the fractions
// only, so faces may run in any order or concurrently.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/mac_layout.h"

namespace vp::kernels {

// theta is clamped below at this value. As theta -> 0 the surface reaches c's centre, the
// diagonal term A_f / theta grows without bound and the velocity update multiplies the
// solver's error in p_c by 1/theta. At 1e-3 the diagonal stays within three orders of the
// ordinary entries (MIC(0) and CG cope: the row becomes nearly Dirichlet, which they handle
// well) and the error the clamp introduces is in a cell whose pressure is itself
// O(theta * rho g h), i.e. below 1e-3 of the hydrostatic jump over one cell.
constexpr double kMinFreeSurfaceTheta = 1e-3;

VP_HOST_DEVICE inline bool isLiquid(double phi) { return phi < 0.0; }

// Where the surface crosses the segment from a liquid cell's centre to an air neighbour's, as
// a fraction of it from the liquid side. phiLiquid < 0 <= phiAir.
VP_HOST_DEVICE inline double freeSurfaceTheta(double phiLiquid, double phiAir) {
  const double theta = phiLiquid / (phiLiquid - phiAir);
  return theta > kMinFreeSurfaceTheta ? theta : kMinFreeSurfaceTheta;
}

// Open fractions below this count as closed. The exact coverage paths leave round-off
// (~1e-15) on faces deep inside a solid; taken literally those make cells inside the solid
// "fluid" with diagonals ~1e-15, which the CG cannot resolve (their pressure and the velocity
// of their faces become garbage). 1e-6 of a face is far above any round-off and far below
// any opening that carries a meaningful flux.
constexpr double kMinOpenFraction = 1e-6;

// A face's collider open fraction as the operator, the right-hand side and the velocity update
// use it (domain Wall faces aside): 0 below kMinOpenFraction.
VP_HOST_DEVICE inline double openedFraction(double fraction) {
  return fraction < kMinOpenFraction ? 0.0 : fraction;
}

// What every face of the update reads.
struct PressureUpdateFields {
  const double* open;           // the face's collider open fraction
  const double* solidVelocity;  // the covering solid's normal velocity, per face
  const double* pressure;       // per cell
  const double* liquidPhi;      // per cell; nullptr for smoke
  double gradientScale;         // dt / (rho h)
};

// Face f between cells cellLow and cellHigh along its axis (-1: beyond an Open domain side,
// where the ghost pressure is 0); wall: f lies on a domain Wall side. A closed face takes the
// solid's velocity; a liquid face with air on both sides keeps its velocity (extrapolation
// fills it); a face between liquid and air reads the ghost pressure at the crossing.
VP_HOST_DEVICE inline void pressureUpdateFace(const PressureUpdateFields& in, int64_t f, bool wall, int64_t cellLow,
                                              int64_t cellHigh, double* u) {
  if (wall) {
    u[f] = 0.0;
    return;
  }
  if (!(openedFraction(in.open[f]) > 0.0)) {
    u[f] = in.solidVelocity[f];
    return;
  }
  const bool hasLow = cellLow >= 0, hasHigh = cellHigh >= 0;
  double pLow = hasLow ? in.pressure[cellLow] : 0.0;
  double pHigh = hasHigh ? in.pressure[cellHigh] : 0.0;
  if (in.liquidPhi != nullptr) {
    const bool liquidLow = hasLow && isLiquid(in.liquidPhi[cellLow]);
    const bool liquidHigh = hasHigh && isLiquid(in.liquidPhi[cellHigh]);
    if (!liquidLow && !liquidHigh) return;
    if (liquidLow && hasHigh && !liquidHigh)
      pHigh = pLow * (1.0 - 1.0 / freeSurfaceTheta(in.liquidPhi[cellLow], in.liquidPhi[cellHigh]));
    else if (liquidHigh && hasLow && !liquidLow)
      pLow = pHigh * (1.0 - 1.0 / freeSurfaceTheta(in.liquidPhi[cellHigh], in.liquidPhi[cellLow]));
  }
  u[f] -= in.gradientScale * (pHigh - pLow);
}

// pressureUpdateFace for a-face (i, j, k) of a grid with layout g.
VP_HOST_DEVICE inline void pressureUpdateFaceAt(const PressureUpdateFields& in, const MacLayout& g, int a, int64_t i,
                                                int64_t j, int64_t k, double* u) {
  const int64_t along = a == 0 ? i : a == 1 ? j : k;
  const int64_t cellLow = along > 0 ? g.cellIndex(i - (a == 0), j - (a == 1), k - (a == 2)) : -1;
  const int64_t cellHigh = along < g.cells(a) ? g.cellIndex(i, j, k) : -1;
  pressureUpdateFace(in, g.faceIndex(a, i, j, k), g.isWall(a, along), cellLow, cellHigh, u);
}

}  // namespace vp::kernels
