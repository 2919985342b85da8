// Kernel bodies of semi-Lagrangian advection on a MAC grid: trilinear stencils, the grid's
// velocity at a point or at a sample, and the midpoint-rule back-trace, as pure functions of
// plain arrays. The CPU runs them stage by stage over batches (runtime/fluid/advection/
// advection_rows.h); a per-sample launcher can call the composed ones (velocityAt,
// traceToLattice) and gets the same bits when it compiles without contraction (nvcc
// --fmad=false). The tests hold the batches to the composed kernels.
//
// Lattices: samples at lattice coordinates 0 .. samples-1 per axis, index i + nx (j + ny k).
// Coordinates outside are clamped to the lattice (constant extrapolation, what a back-traced
// point that leaves the domain wants); NaN clamps to 0 rather than reaching an undefined
// float-to-int conversion.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

// One axis of a trilinear stencil at lattice coordinate g over `samples` samples: the lower
// sample and the weight of the upper one (0 on a lattice of one sample). Branch-free. Real is
// double for advection; float only in BM_AdvectionGatherPrecision (tests/bench), which
// measures what single precision would buy.
template <class Real>
VP_HOST_DEVICE inline void latticeSpan(Real g, int samples, int* base, Real* weight) {
  g = g >= Real(0) ? g : Real(0);  // also NaN
  const Real last = static_cast<Real>(samples - 1);
  g = last < g ? last : g;
  const int lower = samples - 2 > 0 ? samples - 2 : 0;
  const int b = static_cast<int>(g) < lower ? static_cast<int>(g) : lower;
  *base = b;
  *weight = samples > 1 ? g - static_cast<Real>(b) : Real(0);
}

// Index steps of a lattice's three axes (0 along an axis with one sample).
struct LatticeSteps {
  int64_t step[3];
  int64_t stride[3];  // index strides (1, nx, nx ny), whatever the sample counts
};

VP_HOST_DEVICE inline LatticeSteps latticeSteps(const int dims[3]) {
  LatticeSteps s;
  s.stride[0] = 1;
  s.stride[1] = dims[0];
  s.stride[2] = static_cast<int64_t>(dims[0]) * dims[1];
  for (int d = 0; d < 3; ++d) s.step[d] = dims[d] > 1 ? s.stride[d] : 0;
  return s;
}

// A trilinear stencil's 8 samples are corner q = x + 2 y + 4 z: the offset of corner q from the
// lowest one.
VP_HOST_DEVICE inline int64_t cornerOffset(int q, const int64_t step[3]) {
  return ((q & 1) ? step[0] : 0) + ((q & 2) ? step[1] : 0) + ((q & 4) ? step[2] : 0);
}

// The smallest and largest of 8 corner values (in corner order, so signed zeros compare the
// same way whoever calls it).
template <class Real>
VP_HOST_DEVICE inline void cornerRange(const Real c[8], Real* lo, Real* hi) {
  Real l = c[0], h = c[0];
  for (int q = 1; q < 8; ++q) {
    l = c[q] < l ? c[q] : l;
    h = h < c[q] ? c[q] : h;
  }
  *lo = l;
  *hi = h;
}

// Trilinear interpolation of 8 corner values with the upper corners' weights w0, w1, w2 (x
// first, then y, then z).
template <class Real>
VP_HOST_DEVICE inline Real trilinearCorners(const Real c[8], Real w0, Real w1, Real w2) {
  const Real x00 = c[0] + w0 * (c[1] - c[0]), x10 = c[2] + w0 * (c[3] - c[2]);
  const Real x01 = c[4] + w0 * (c[5] - c[4]), x11 = c[6] + w0 * (c[7] - c[6]);
  const Real y0 = x00 + w1 * (x10 - x00), y1 = x01 + w1 * (x11 - x01);
  return y0 + w2 * (y1 - y0);
}

// Trilinear interpolation of the 8 samples from p with the upper samples' weights w0, w1, w2.
// lo/hi (optional) receive the smallest and largest sample.
VP_HOST_DEVICE inline double trilinear(const double* p, const int64_t step[3], double w0, double w1, double w2,
                                       double* lo = nullptr, double* hi = nullptr) {
  double c[8];
  for (int q = 0; q < 8; ++q) c[q] = p[cornerOffset(q, step)];
  if (lo != nullptr) cornerRange(c, lo, hi);
  return trilinearCorners(c, w0, w1, w2);
}

// A MAC grid's velocity as plain arrays: u[a] holds the a-faces, faceDims[a] their lattice
// (cells + 1 along a).
struct MacVelocityView {
  const double* u[3];
  int faceDims[3][3];
  double origin[3];
  double h, invH;
};

// The velocity at world point x. Each axis has two lattices (face-centred along the component's
// own axis, cell-centred along the others): their spans are computed once per axis and shared
// by the three components. In two stages, so a batch can run each over many points in turn:
// the coordinate of x[d] on axis d's lattice (0: cell-centred, 1: face-centred), of
// velocityLatticeSamples(v, d, lattice) samples; then one component from the spans.
VP_HOST_DEVICE inline double velocityLatticeCoordinate(const MacVelocityView& v, int d, double x, int lattice) {
  return (x - v.origin[d]) * v.invH - 0.5 + 0.5 * lattice;
}
VP_HOST_DEVICE inline int velocityLatticeSamples(const MacVelocityView& v, int d, int lattice) {
  return v.faceDims[d][d] - 1 + lattice;
}
VP_HOST_DEVICE inline double velocityComponent(const MacVelocityView& v, int a, const int base[2][3],
                                               const double weight[2][3]) {
  const LatticeSteps s = latticeSteps(v.faceDims[a]);
  int64_t index = 0;
  double w[3];
  for (int d = 0; d < 3; ++d) {
    index += base[d == a][d] * s.stride[d];
    w[d] = weight[d == a][d];
  }
  return trilinear(v.u[a] + index, s.step, w[0], w[1], w[2]);
}
VP_HOST_DEVICE inline void velocityAt(const MacVelocityView& v, const double x[3], double out[3]) {
  int base[2][3];
  double weight[2][3];
  for (int d = 0; d < 3; ++d)
    for (int lattice = 0; lattice < 2; ++lattice)
      latticeSpan(velocityLatticeCoordinate(v, d, x[d], lattice), velocityLatticeSamples(v, d, lattice),
                  &base[lattice][d], &weight[lattice][d]);
  for (int a = 0; a < 3; ++a) out[a] = velocityComponent(v, a, base, weight);
}

// Index of sample `at` in a lattice of dims samples per axis.
VP_HOST_DEVICE inline int64_t latticeIndex(const int dims[3], const int at[3]) {
  return at[0] + at[1] * static_cast<int64_t>(dims[0]) + at[2] * (static_cast<int64_t>(dims[0]) * dims[1]);
}

// Component b (!= a) at the centre of a-face (i, j, k): the mean of the four b-faces around it
// (what trilinear sampling gives there, without its cost); at the domain's a-sides the face has
// cells on one side only and takes that side's pair. In two parts, so a batch can run each over
// many faces in turn: where the four lie (the first one's index in u[b], the two pairs' distance
// along a in *shift; a pair's second face is one b-step further), then their mean.
VP_HOST_DEVICE inline int64_t faceMeanFirst(const MacVelocityView& v, int a, int b, const int face[3],
                                            int64_t* shift) {
  const int* d = v.faceDims[b];
  const int cellsA = d[a];  // b-faces have as many entries along a as there are cells
  const int lo = face[a] - 1 > 0 ? face[a] - 1 : 0;
  const int hi = face[a] < cellsA - 1 ? face[a] : cellsA - 1;
  int c[3] = {face[0], face[1], face[2]};
  c[a] = lo;
  const int64_t strideA = a == 0 ? 1 : a == 1 ? d[0] : static_cast<int64_t>(d[0]) * d[1];
  *shift = (hi - lo) * strideA;
  return latticeIndex(d, c);
}
VP_HOST_DEVICE inline double faceMean(const double* p, int64_t stepB, int64_t shift) {
  return 0.25 * (p[0] + p[stepB] + p[shift] + p[shift + stepB]);
}
VP_HOST_DEVICE inline double otherComponentAtFace(const MacVelocityView& v, int a, int b, const int face[3]) {
  int64_t shift;
  const int64_t first = faceMeanFirst(v, a, b, face, &shift);
  return faceMean(v.u[b] + first, latticeSteps(v.faceDims[b]).stride[b], shift);
}

// Component b at the centre of a cell whose lower b-face is p: the mean of its two b-faces.
VP_HOST_DEVICE inline double cellMean(const double* p, int64_t stepB) { return 0.5 * (p[0] + p[stepB]); }

// The velocity at the centre of a-face `at` (a = 3: of cell `at`): a face has its own
// component and otherComponentAtFace for the other two; a cell the mean of its two faces per
// axis.
VP_HOST_DEVICE inline void velocityAtSample(const MacVelocityView& v, int a, const int at[3], double u[3]) {
  for (int b = 0; b < 3; ++b) {
    if (a != 3 && b != a) {
      u[b] = otherComponentAtFace(v, a, b, at);
      continue;
    }
    // A cell's b-faces, or the face's own: `at` indexes the b-face lattice.
    const double* p = v.u[b] + latticeIndex(v.faceDims[b], at);
    u[b] = a == 3 ? cellMean(p, latticeSteps(v.faceDims[b]).stride[b]) : p[0];
  }
}

// World position of a-face (i, j, k) (a = 3: the cell centre).
VP_HOST_DEVICE inline void sampleCentre(const MacVelocityView& v, int a, const int at[3], double x[3]) {
  for (int d = 0; d < 3; ++d) x[d] = v.origin[d] + v.h * (at[d] + 0.5);
  if (a < 3) x[a] -= 0.5 * v.h;
}

// The lattice coordinate of world point x among a-faces (a = 3: cell centres).
VP_HOST_DEVICE inline void latticeCoordinate(const MacVelocityView& v, int a, const double x[3], double g[3]) {
  for (int d = 0; d < 3; ++d) g[d] = (x[d] - v.origin[d]) / v.h - 0.5;
  if (a < 3) g[a] += 0.5;
}

// Midpoint-rule back-trace over dt (negative dt traces forward in time) from x, where the
// velocity is u0: x - dt u(x - dt/2 u0). Split in its two halves so a batch can run each over
// many points in turn.
VP_HOST_DEVICE inline void traceMidpoint(const double x[3], const double u0[3], double dt, double mid[3]) {
  const double half = 0.5 * dt;
  for (int d = 0; d < 3; ++d) mid[d] = x[d] - half * u0[d];
}
VP_HOST_DEVICE inline void traceEnd(const double x[3], const double uMid[3], double dt, double end[3]) {
  for (int d = 0; d < 3; ++d) end[d] = x[d] - dt * uMid[d];
}

// The whole trace of one sample at x (velocity u0 there) over dt, as a coordinate g of the
// lattice of latticeAxis's faces (3: cells).
VP_HOST_DEVICE inline void traceToLattice(const MacVelocityView& v, const double x[3], const double u0[3], double dt,
                                          int latticeAxis, double g[3]) {
  double mid[3], uMid[3], end[3];
  traceMidpoint(x, u0, dt, mid);
  velocityAt(v, mid, uMid);
  traceEnd(x, uMid, dt, end);
  latticeCoordinate(v, latticeAxis, end, g);
}

// MacCormack's backward step samples the forward field where a sample goes over dt. It is taken
// as the sample's back-trace g reflected through the sample's own lattice coordinate `at`
// (2 at - g), not as a second trace forward in time: the two differ by dt^2 (u . grad) u, the
// order of the midpoint rule's own error, and the reflection needs no velocity samples.
VP_HOST_DEVICE inline void reflectThrough(const int at[3], const double g[3], double ahead[3]) {
  for (int d = 0; d < 3; ++d) ahead[d] = 2.0 * at[d] - g[d];
}

// A trilinear sample of `values` (a lattice of dims samples per axis) at lattice coordinate g;
// lo/hi (optional, together) receive the range of the 8 samples used.
VP_HOST_DEVICE inline double sampleLattice(const double* values, const int dims[3], const double g[3],
                                           double* lo = nullptr, double* hi = nullptr) {
  const LatticeSteps st = latticeSteps(dims);
  int base[3];
  double w[3];
  for (int d = 0; d < 3; ++d) latticeSpan(g[d], dims[d], &base[d], &w[d]);
  const int64_t index = base[0] * st.stride[0] + base[1] * st.stride[1] + base[2] * st.stride[2];
  return trilinear(values + index, st.step, w[0], w[1], w[2], lo, hi);
}

// Which faces of each cell of a cell-centred lattice are open, for sampling that does not
// interpolate across solids (connectedSample):
//   faces[c]      bit 2 * axis + high: that face of cell c is open; bit kCellIsFluid: c has an
//                 open face at all
//   blockOpen[c]  1 when the 2 x 2 x 2 block whose lowest cell is c has all its inner faces
//                 open (12, fewer along an axis with one cell), i.e. it interpolates as usual
constexpr uint8_t kCellIsFluid = 1 << 6;

// Trilinear interpolation at lattice coordinate g restricted to the samples that the open faces
// connect, inside the 2 x 2 x 2 block, to the fluid sample with the largest weight (the
// "anchor"; the lowest corner among equal weights); the weights of the connected samples are
// renormalized and lo/hi (optional, together) cover them only. A block with every inner face
// open gives sampleLattice's value; a block with no fluid cell interpolates as usual (its
// values are the solid ones).
VP_HOST_DEVICE inline double connectedSample(const double* values, const int dims[3], const double g[3],
                                             const uint8_t* faces, const uint8_t* blockOpen, double* lo = nullptr,
                                             double* hi = nullptr) {
  const LatticeSteps st = latticeSteps(dims);
  int corner[3];
  double w[3];
  int64_t base = 0;
  for (int d = 0; d < 3; ++d) {
    latticeSpan(g[d], dims[d], &corner[d], &w[d]);
    base += corner[d] * st.stride[d];
  }
  if (blockOpen[base]) return trilinear(values + base, st.step, w[0], w[1], w[2], lo, hi);
  int64_t index[8];
  double weight[8];
  int anchor = -1;
  for (int q = 0; q < 8; ++q) {
    index[q] = base + cornerOffset(q, st.step);
    weight[q] = ((q & 1) ? w[0] : 1.0 - w[0]) * ((q & 2) ? w[1] : 1.0 - w[1]) * ((q & 4) ? w[2] : 1.0 - w[2]);
    if ((faces[index[q]] & kCellIsFluid) && (anchor < 0 || weight[q] > weight[anchor])) anchor = q;
  }
  if (anchor < 0) return trilinear(values + base, st.step, w[0], w[1], w[2], lo, hi);
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
      const bool open = st.step[a] == 0 || (faces[index[q]] & (1u << (2 * a + ((q >> a) & 1 ? 0 : 1)))) != 0;
      if (open) {
        reached |= 1u << other;
        stack[top++] = other;
      }
    }
  }
  double sum = 0.0, weightSum = 0.0;
  double low = values[index[anchor]], high = low;
  for (int q = 0; q < 8; ++q) {
    if (!(reached & (1u << q))) continue;
    const double v = values[index[q]];
    sum += weight[q] * v;
    weightSum += weight[q];
    low = v < low ? v : low;
    high = high < v ? v : high;
  }
  if (lo != nullptr) *lo = low, *hi = high;
  // Zero weight on every connected sample: the point sits on a sample that is not connected
  // (a solid cell's centre); the anchor's value is the nearest connected one.
  return weightSum > 0.0 ? sum / weightSum : values[index[anchor]];
}

// Where a-face `at`'s centre came from over dt through v's velocity, as a coordinate of the
// a-face lattice.
VP_HOST_DEVICE inline void traceFace(const MacVelocityView& v, int a, const int at[3], double dt, double g[3]) {
  double x[3], u0[3];
  sampleCentre(v, a, at, x);
  velocityAtSample(v, a, at, u0);
  traceToLattice(v, x, u0, dt, a, g);
}

// The semi-Lagrangian value of a-face `at` over dt: `field` (a lattice of a-faces) sampled where
// the face's centre came from; lo/hi (optional) the stencil's range.
VP_HOST_DEVICE inline double advectFace(const MacVelocityView& v, int a, const int at[3], double dt,
                                        const double* field, double* lo = nullptr, double* hi = nullptr) {
  double g[3];
  traceFace(v, a, at, dt, g);
  return sampleLattice(field, v.faceDims[a], g, lo, hi);
}

// MacCormack's value from the forward (semi-Lagrangian) value, the old one, the forward field
// traced back again, and the range [lo, hi] of the samples the forward step read. Where the
// correction leaves that range the forward value is kept (Selle et al.'s own limiter) rather
// than the correction clamped to it: clamped, every such face took the extreme of its stencil,
// which near a free surface (extrapolated air velocities in the stencil) pumped energy in step
// after step, and a stirred tank ran away (fluid_paddle_buoy_test.cpp).
VP_HOST_DEVICE inline double maccormackValue(double forward, double old, double backAgain, double lo, double hi) {
  const double corrected = forward + 0.5 * (old - backAgain);
  return corrected >= lo && corrected <= hi ? corrected : forward;
}

// MacCormack's value of a-face `at` (index f in its lattice) over dt: `forward` holds every
// a-face's advectFace over dt, lo/hi this face's range from it; the backward step samples it at
// the back-trace's reflection (reflectThrough).
VP_HOST_DEVICE inline double maccormackFace(const MacVelocityView& v, int a, const int at[3], int64_t f, double dt,
                                            const double* old, const double* forward, double lo, double hi) {
  double g[3], ahead[3];
  traceFace(v, a, at, dt, g);
  reflectThrough(at, g, ahead);
  return maccormackValue(forward[f], old[f], sampleLattice(forward, v.faceDims[a], ahead), lo, hi);
}

}  // namespace vp::kernels
