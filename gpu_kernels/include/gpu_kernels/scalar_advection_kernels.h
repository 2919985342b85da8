// Kernel bodies of cell-centred scalar advection (runtime/fluid/advection/advection.h has the
// method): one cell's trace, its semi-Lagrangian and MacCormack values under the cell rules
// (solid cells, kept cells, sampling through open faces), and the conserved field's totals.
// The CPU runs the traces and samples in batches (advection_rows.h) and these per cell; a
// device runs them one thread per cell (per row for the row sums). Liquid level sets'
// rule beyond Open sides is the CPU's only.
#pragma once

#include <cstdint>

#include "gpu_kernels/advection_kernels.h"
#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/mac_layout.h"

namespace vp::kernels {

// Where cell `at`'s centre came from over dt, in cell-lattice coordinates.
VP_HOST_DEVICE inline void traceCell(const MacVelocityView& v, const int at[3], double dt, double g[3]) {
  double x[3], u0[3];
  sampleCentre(v, 3, at, x);
  velocityAtSample(v, 3, at, u0);
  traceToLattice(v, x, u0, dt, 3, g);
}

// What a scalar pass asks of a cell besides its trace: is it solid (no open face: it is not
// advected and holds the solid value), does it keep its value (keepBeyond); and how the old
// field is sampled (through open faces only, or plainly).
struct ScalarCellRules {
  const uint8_t* faces;       // null: no open-face masks
  const uint8_t* blockOpen;
  const uint8_t* kept;        // null: keepBeyond off
  const double* solidValue;   // null: solid cells keep their values
  int dims[3];

  VP_HOST_DEVICE bool solid(int64_t c) const { return faces != nullptr && !(faces[c] & kCellIsFluid); }
  VP_HOST_DEVICE bool keeps(int64_t c) const { return kept != nullptr && kept[c]; }
  VP_HOST_DEVICE bool advected(int64_t c) const { return !solid(c) && !keeps(c); }
  // The value of a cell that is not advected: its solid value, or its old one.
  VP_HOST_DEVICE double unadvected(const double* old, int64_t c) const {
    return solid(c) && solidValue != nullptr ? *solidValue : old[c];
  }
  // values at lattice coordinate g; lo/hi (optional, together) the range of the samples used.
  VP_HOST_DEVICE double sample(const double* values, const double g[3], double* lo, double* hi) const {
    return faces != nullptr ? connectedSample(values, dims, g, faces, blockOpen, lo, hi)
                            : sampleLattice(values, dims, g, lo, hi);
  }
};

// The forward (semi-Lagrangian) pass at cell c traced back to g: forward[c], and for MacCormack
// (lo, hi not null) the range of the samples it read. A cell that is not advected takes its
// solid value or keeps its old one, and that value is its range.
VP_HOST_DEVICE inline void scalarForwardCell(const ScalarCellRules& rules, const double* old, int64_t c,
                                             const double g[3], double* forward, double* lo, double* hi) {
  if (!rules.advected(c)) {
    forward[c] = rules.unadvected(old, c);
    if (lo != nullptr) lo[c] = hi[c] = forward[c];
    return;
  }
  forward[c] = rules.sample(old, g, lo != nullptr ? lo + c : nullptr, hi != nullptr ? hi + c : nullptr);
}

// MacCormack's value for a scalar: the corrected value clamped to the range [lo, hi] of the
// samples the forward step read (a scalar may take the range's end, unlike a velocity:
// maccormackValue), so the correction never creates new extrema.
VP_HOST_DEVICE inline double maccormackClamped(double forward, double old, double backAgain, double lo, double hi) {
  const double corrected = forward + 0.5 * (old - backAgain);
  return corrected < lo ? lo : hi < corrected ? hi : corrected;
}

// MacCormack's value at cell c from the forward field traced ahead to gAhead; a cell that is not
// advected keeps its forward value.
VP_HOST_DEVICE inline double scalarCorrectionCell(const ScalarCellRules& rules, const double* old,
                                                  const double* forward, int64_t c, const double gAhead[3],
                                                  double lo, double hi) {
  if (!rules.advected(c)) return forward[c];
  return maccormackClamped(forward[c], old[c], rules.sample(forward, gAhead, nullptr, nullptr), lo, hi);
}

// Sum of row `row` (j + ny k) of a cell-centred field, in cell order.
VP_HOST_DEVICE inline double cellRowSum(const double* values, int64_t nx, int64_t row) {
  const double* v = values + row * nx;
  double sum = 0.0;
  for (int64_t i = 0; i < nx; ++i) sum += v[i];
  return sum;
}

// What the outward velocities of the Open domain sides carry out of their boundary cells' values
// over dt (a face passes u dt h^2 of volume, a cell holds h^3), in value x cells: sides in
// MacGrid::sides order, each side's faces row by row. One thread's serial sum.
VP_HOST_DEVICE inline double openSideOutflow(const MacLayout& g, const double* const velocity[3], const double* values,
                                             double dt, double h) {
  const int64_t n[3] = {g.nx, g.ny, g.nz};
  double out = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int high = 0; high < 2; ++high) {
      if (g.wall[2 * a + high]) continue;
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      for (int64_t q = 0; q < n[c]; ++q)
        for (int64_t p = 0; p < n[b]; ++p) {
          int64_t face[3], cell[3];
          face[a] = high ? n[a] : 0;
          cell[a] = high ? n[a] - 1 : 0;
          face[b] = cell[b] = p;
          face[c] = cell[c] = q;
          const double u = velocity[a][g.faceIndex(a, face[0], face[1], face[2])];
          const double outward = high ? u : -u;
          if (outward > 0.0) out += outward * dt / h * values[g.cellIndex(cell[0], cell[1], cell[2])];
        }
    }
  return out;
}

// The conserved field's scale after advection: its total brought back to the target (the total
// before less the open sides' outflow, at least 0); 1 when nothing is left to scale.
VP_HOST_DEVICE inline double conservationScale(double target, double total) {
  return total > 0.0 ? (target < 0.0 ? 0.0 : target) / total : 1.0;
}

}  // namespace vp::kernels
