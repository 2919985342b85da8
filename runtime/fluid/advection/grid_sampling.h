// Trilinear interpolation on a regular lattice of samples, shared by the MAC grid's velocity
// and scalar sampling and by advection (which also needs the range of the 8 samples used,
// for MacCormack's clamp), and its variant restricted to the cells that open faces connect
// (connectedTrilinearSample: smoke does not get interpolated through thin solids).
//
// Samples sit at lattice coordinates 0 .. dims-1 per axis, index i + dims.x * (j + dims.y * k).
// Coordinates outside the lattice are clamped to it (constant extrapolation), which is what
// semi-Lagrangian advection wants for back-traced points that leave the domain; NaN clamps
// to 0 instead of reaching an undefined float-to-int conversion.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "gpu_kernels/advection_kernels.h"

namespace vp {

struct SampleRange {
  double lo = 0.0, hi = 0.0;
};

// The 8 samples around a lattice coordinate: base index, per-axis index steps (0 along an axis
// with a single sample) and the weights of the upper samples.
struct TrilinearStencil {
  size_t base;
  int64_t step[3];
  double weight[3];
};

inline TrilinearStencil trilinearStencil(const Eigen::Vector3i& dims, const Eigen::Vector3d& g) {
  const int n[3] = {dims[0], dims[1], dims[2]};
  const kernels::LatticeSteps steps = kernels::latticeSteps(n);
  TrilinearStencil s;
  s.base = 0;
  for (int d = 0; d < 3; ++d) {
    int b;
    kernels::latticeSpan(g[d], n[d], &b, &s.weight[d]);
    s.base += static_cast<size_t>(b) * static_cast<size_t>(steps.stride[d]);
    s.step[d] = steps.step[d];
  }
  return s;
}

inline double trilinearSample(const double* values, const TrilinearStencil& s, SampleRange* range = nullptr) {
  return kernels::trilinear(values + s.base, s.step, s.weight[0], s.weight[1], s.weight[2],
                            range != nullptr ? &range->lo : nullptr, range != nullptr ? &range->hi : nullptr);
}

// `range` (optional) receives the smallest and largest of the 8 samples.
inline double trilinearSample(const double* values, const Eigen::Vector3i& dims, const Eigen::Vector3d& g,
                              SampleRange* range = nullptr) {
  return trilinearSample(values, trilinearStencil(dims, g), range);
}

// Which faces of each cell of a cell-centred lattice are open, for sampling that does not
// interpolate across solids (see connectedTrilinearSample).
//   faces[c]      bit 2 * axis + high: that face of cell c is open; bit kCellIsFluid: c has an
//                 open face at all
//   blockOpen[c]  1 when the 2 x 2 x 2 block whose lowest cell is c has all its inner faces
//                 open (12, fewer along an axis with one cell), i.e. it interpolates as usual
constexpr uint8_t kCellIsFluid = 1 << 6;

// Trilinear interpolation restricted to the samples that the open faces connect, inside the
// 2 x 2 x 2 block, to the fluid sample with the largest weight (the "anchor"; the lowest
// corner among equal weights); the weights of the connected samples are renormalized and
// `range` covers them only. Blocks with every inner face open give trilinearSample's value.
// A block with no fluid cell interpolates as usual (its values are the solid ones).
inline double connectedTrilinearSample(const double* values, const Eigen::Vector3i& dims, const Eigen::Vector3d& g,
                                       const uint8_t* faces, const uint8_t* blockOpen, SampleRange* range = nullptr) {
  const TrilinearStencil s = trilinearStencil(dims, g);
  if (blockOpen[s.base]) return trilinearSample(values, s, range);
  size_t index[8];
  double weight[8];
  int anchor = -1;
  for (int q = 0; q < 8; ++q) {
    index[q] = s.base + ((q & 1) ? s.step[0] : 0) + ((q & 2) ? s.step[1] : 0) + ((q & 4) ? s.step[2] : 0);
    weight[q] = ((q & 1) ? s.weight[0] : 1.0 - s.weight[0]) * ((q & 2) ? s.weight[1] : 1.0 - s.weight[1]) *
                ((q & 4) ? s.weight[2] : 1.0 - s.weight[2]);
    if ((faces[index[q]] & kCellIsFluid) && (anchor < 0 || weight[q] > weight[anchor])) anchor = q;
  }
  if (anchor < 0) return trilinearSample(values, s, range);
  // Flood fill over the block's corners through open inner faces (8 corners, 12 faces).
  unsigned reached = 1u << anchor;
  int stack[8], top = 0;
  stack[top++] = anchor;
  while (top > 0) {
    const int q = stack[--top];
    for (int a = 0; a < 3; ++a) {
      const int other = q ^ (1 << a);
      if (reached & (1u << other)) continue;
      // q's face towards `other`: its high face when q is the lower corner along a.
      const bool open = s.step[a] == 0 || (faces[index[q]] & (1u << (2 * a + ((q >> a) & 1 ? 0 : 1)))) != 0;
      if (open) {
        reached |= 1u << other;
        stack[top++] = other;
      }
    }
  }
  double sum = 0.0, weightSum = 0.0;
  double lo = values[index[anchor]], hi = lo;
  for (int q = 0; q < 8; ++q) {
    if (!(reached & (1u << q))) continue;
    const double v = values[index[q]];
    sum += weight[q] * v;
    weightSum += weight[q];
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (range != nullptr) range->lo = lo, range->hi = hi;
  // Zero weight on every connected sample: the point sits on a sample that is not connected
  // (a solid cell's centre); the anchor's value is the nearest connected one.
  return weightSum > 0.0 ? sum / weightSum : values[index[anchor]];
}

}  // namespace vp
