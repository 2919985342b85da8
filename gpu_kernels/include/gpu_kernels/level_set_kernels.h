// Kernel bodies of the liquid level set's upkeep: redistancing (runtime/fluid/surface/
// level_set_redistance.h: the Godunov upwind update of |grad d| = 1, one cell's update in a
// red-black Gauss-Seidel sweep over the band, the signed, clamped result) and the volume
// measure its correction keeps (runtime/fluid/surface/liquid_volume.h: the smoothed Heaviside
// and its slope).
#pragma once

#include <cmath>
#include <cstdint>

#include "gpu_kernels/cell_lattice.h"
#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/mac_layout.h"
#include "gpu_kernels/pressure_update_kernels.h"

namespace vp::kernels {

// Sheets thinner than a cell, for a semi-Lagrangian level set (runtime/fluid/advection/
// advection.h). A liquid cell whose two neighbours along an axis are air and whose two faces
// on that axis both flow in is a sheet the projection closes from both sides; the inflows
// average to nothing at the cell centre the level set is traced from, so the traced value
// never sees the sheet thin, and left alone such a sheet neither thins nor drains
// (docs/choices.md). Each of its surfaces moves in at its face's inflow, so the centre's
// distance to the nearer one shrinks at least at the smaller inflow: that speed (m/s, the
// largest over the axes), 0 for any other cell. Cells on the domain's sides along an axis have
// no sheet along it.
VP_HOST_DEVICE inline double sheetClosingSpeed(const MacLayout& g, const double* phi, const double* const u[3],
                                               int64_t i, int64_t j, int64_t k) {
  const int64_t c = g.cellIndex(i, j, k);
  if (!isLiquid(phi[c])) return 0.0;
  const int64_t at[3] = {i, j, k};
  const int64_t stride[3] = {1, g.nx, g.nx * g.ny};
  double speed = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (at[a] == 0 || at[a] + 1 == g.cells(a)) continue;
    if (isLiquid(phi[c - stride[a]]) || isLiquid(phi[c + stride[a]])) continue;
    const double inLow = u[a][g.faceIndex(a, i, j, k)];
    const double inHigh = -u[a][g.faceIndex(a, i + (a == 0), j + (a == 1), k + (a == 2))];
    const double closing = inLow < inHigh ? inLow : inHigh;
    speed = closing > speed ? closing : speed;
  }
  return speed;
}

// +inf: a distance not reached yet.
VP_HOST_DEVICE inline double unreachedDistance() { return HUGE_VAL; }

// d with |grad d| = 1 from the smaller neighbour value along each axis (a, b, c), spacing h.
VP_HOST_DEVICE inline double eikonalUpdate(double a, double b, double c, double h) {
  double t;
  if (a > b) t = a, a = b, b = t;
  if (b > c) t = b, b = c, c = t;
  if (a > b) t = a, a = b, b = t;
  double d = a + h;
  if (d <= b) return d;
  d = 0.5 * (a + b + std::sqrt(2.0 * h * h - (a - b) * (a - b)));
  if (d <= c) return d;
  const double s = a + b + c;
  return (s + std::sqrt(s * s - 3.0 * (a * a + b * b + c * c - h * h))) / 3.0;
}

// Cell c's update in a sweep (ijk: its coordinates): the upwind value from its neighbours
// inside the grid, kept when smaller. Returns how much it dropped where the new value lies under `clamp` (values
// at or above it never reach one under it), +inf for a first value under it, else 0.
VP_HOST_DEVICE inline double redistanceSweepCellAt(const CellLattice& g, int64_t c, const int64_t ijk[3], double clamp,
                                                   double* distance) {
  const double unreached = unreachedDistance();
  double upwind[3];
  for (int a = 0; a < 3; ++a) {
    const double minus = ijk[a] > 0 ? distance[c - g.stride[a]] : unreached;
    const double plus = ijk[a] + 1 < g.n[a] ? distance[c + g.stride[a]] : unreached;
    upwind[a] = plus < minus ? plus : minus;
  }
  const double lowestXY = upwind[1] < upwind[0] ? upwind[1] : upwind[0];
  const double lowest = upwind[2] < lowestXY ? upwind[2] : lowestXY;
  if (lowest == unreached) return 0.0;  // no neighbour reached yet
  const double updated = eikonalUpdate(upwind[0], upwind[1], upwind[2], g.h);
  if (!(updated < distance[c])) return 0.0;
  const double before = distance[c];
  distance[c] = updated;
  if (!(updated < clamp)) return 0.0;
  return before == unreached ? unreached : before - updated;
}
// The same with c's coordinates worked out.
VP_HOST_DEVICE inline double redistanceSweepCell(const CellLattice& g, int64_t c, double clamp, double* distance) {
  int64_t ijk[3];
  g.coordinates(c, ijk);
  return redistanceSweepCellAt(g, c, ijk, clamp, distance);
}

// redistanceSweepCell for a cell that a sweep may skip: stale[c] says whether a neighbour's
// distance changed since c's last update. The update is a function of the neighbours and c's
// own value, which only c changes, so a cell with no stale flag would keep its value: skipping
// it gives the same distances, bit for bit, and a drop of 0. A cell that changes raises the
// flags of its neighbours (the other colour, which no one reads in this half-sweep).
VP_HOST_DEVICE inline double redistanceSweepStaleCell(const CellLattice& g, int64_t c, double clamp, double* distance,
                                                      uint8_t* stale) {
  if (!stale[c]) return 0.0;
  stale[c] = 0;
  int64_t ijk[3];
  g.coordinates(c, ijk);
  const double before = distance[c];
  const double drop = redistanceSweepCellAt(g, c, ijk, clamp, distance);
  if (distance[c] == before) return drop;
  for (int a = 0; a < 3; ++a) {
    if (ijk[a] > 0) raiseSharedFlag(&stale[c - g.stride[a]]);
    if (ijk[a] + 1 < g.n[a]) raiseSharedFlag(&stale[c + g.stride[a]]);
  }
  return drop;
}

// The level set at cell c from its unsigned distance: the sign phi had, the size clamped.
VP_HOST_DEVICE inline void writeSignedDistance(int64_t c, double distance, double clamp, double* phi) {
  const double d = clamp < distance ? clamp : distance;
  phi[c] = isLiquid(phi[c]) ? -d : d;
}

// H(phi), the smoothed liquid fraction of a cell for half-width `width` (metres): 1 for
// phi <= -width, 0 for phi >= width, (1 - phi/width - sin(pi phi/width)/pi) / 2 between.
VP_HOST_DEVICE inline double smoothedLiquidFraction(double phi, double width) {
  if (phi <= -width) return 1.0;
  if (phi >= width) return 0.0;
  return 0.5 * (1.0 - phi / width - std::sin(M_PI * phi / width) / M_PI);
}

// dH/dphi.
VP_HOST_DEVICE inline double liquidFractionSlope(double phi, double width) {
  if (phi <= -width || phi >= width) return 0.0;
  return -0.5 * (1.0 + std::cos(M_PI * phi / width)) / width;
}

}  // namespace vp::kernels
