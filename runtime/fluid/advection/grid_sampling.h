// Trilinear interpolation on a regular lattice of samples, shared by the MAC grid's velocity
// and scalar sampling and by advection (which also needs the range of the 8 samples used,
// for MacCormack's clamp), and its variant restricted to the cells that open faces connect
// (connectedTrilinearSample: smoke does not get interpolated through thin solids), over the
// kernel bodies of gpu_kernels/advection_kernels.h.
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

// Sampling through open faces only (kernels::connectedSample, kernels::kCellIsFluid: the masks'
// layout and the rule).
using kernels::kCellIsFluid;

inline double connectedTrilinearSample(const double* values, const Eigen::Vector3i& dims, const Eigen::Vector3d& g,
                                       const uint8_t* faces, const uint8_t* blockOpen, SampleRange* range = nullptr) {
  const int n[3] = {dims[0], dims[1], dims[2]};
  const double at[3] = {g[0], g[1], g[2]};
  return kernels::connectedSample(values, n, at, faces, blockOpen, range != nullptr ? &range->lo : nullptr,
                                  range != nullptr ? &range->hi : nullptr);
}

}  // namespace vp
