// Batched advection stages over the kernels of gpu_kernels/advection_kernels.h (see
// advection_rows.h).
#include "fluid/advection/advection_rows.h"

#include "core/isa_clones.h"
#include "fluid/advection/grid_sampling.h"

namespace vp {
namespace {

// Stencil spans of one batch on one lattice: per axis the lower sample and the upper weight.
struct SpanBatch {
  int base[3][kTraceBatch];
  double weight[3][kTraceBatch];
};

void spansAt(const double (&g)[3][kTraceBatch], int count, const int samples[3], SpanBatch* out) {
  for (int d = 0; d < 3; ++d) {
    const int n = samples[d];
    const double* gd = g[d];
    int* base = out->base[d];
    double* weight = out->weight[d];
    for (int s = 0; s < count; ++s) kernels::latticeSpan(gd[s], n, &base[s], &weight[s]);
  }
}

// Trilinear samples of `values` at a batch of stencils (lowest corners index, upper weights w0,
// w1, w2): each corner's loads as a loop of their own, which the compiler turns into vector
// gathers, then the interpolation (kernels::trilinearCorners) over the batch. lo/hi (optional,
// together) receive each stencil's range.
VP_CLONE_INLINE inline void trilinearBatch(const double* values, const int64_t step[3], const int64_t* index,
                                           const double* w0, const double* w1, const double* w2, int count,
                                           double* out, double* lo = nullptr, double* hi = nullptr) {
  double corners[8][kTraceBatch];
  for (int q = 0; q < 8; ++q) {
    const int64_t offset = kernels::cornerOffset(q, step);
    double* c = corners[q];
    for (int s = 0; s < count; ++s) c[s] = values[index[s] + offset];
  }
  for (int s = 0; s < count; ++s) {
    double c[8];
    for (int q = 0; q < 8; ++q) c[q] = corners[q][s];
    if (lo != nullptr) kernels::cornerRange(c, &lo[s], &hi[s]);
    out[s] = kernels::trilinearCorners(c, w0[s], w1[s], w2[s]);
  }
}

// The lowest corners of a batch's stencils.
VP_CLONE_INLINE inline void stencilIndices(const SpanBatch& x, const SpanBatch& y, const SpanBatch& z,
                                           const int64_t stride[3], int count, int64_t* index) {
  for (int s = 0; s < count; ++s)
    index[s] = x.base[0][s] * stride[0] + y.base[1][s] * stride[1] + z.base[2][s] * stride[2];
}

}  // namespace

kernels::MacVelocityView macVelocityView(const MacGrid& grid) {
  kernels::MacVelocityView v;
  for (int a = 0; a < 3; ++a) {
    v.u[a] = grid.velocity[a].data();
    const Eigen::Vector3i d = grid.faceDims(a);
    for (int e = 0; e < 3; ++e) v.faceDims[a][e] = d[e];
  }
  for (int d = 0; d < 3; ++d) v.origin[d] = grid.spec.origin[d];
  v.h = grid.spec.h;
  v.invH = 1.0 / grid.spec.h;
  return v;
}

// The batch functions work on a local copy of the view: the batches' stores are doubles, as are
// the view's origin and spacing, so through a reference every store would force them (and the
// loop-invariant strides derived from them) to be reloaded.

// kernels::sampleCentre and kernels::velocityAtSample, stage by stage: per axis the row's
// coordinate or each sample's, then per component the samples' first face index (and, for a
// mean of four faces, the pairs' distance), then the values.
VP_ISA_CLONES
void fillTraceStarts(const kernels::MacVelocityView& view, TraceStarts* t) {
  const kernels::MacVelocityView v = view;
  const int a = t->axis, count = t->count;
  t->x.count = t->u0.count = count;
  const int* i = t->i;
  const double half = 0.5 * v.h;
  for (int s = 0; s < count; ++s) {
    t->x.at[0][s] = v.origin[0] + v.h * (i[s] + 0.5);
    if (a == 0) t->x.at[0][s] -= half;
  }
  for (int d = 1; d < 3; ++d) {
    double x = v.origin[d] + v.h * ((d == 1 ? t->j : t->k) + 0.5);
    if (a == d) x -= half;
    for (int s = 0; s < count; ++s) t->x.at[d][s] = x;
  }
  for (int b = 0; b < 3; ++b) {
    const double* u = v.u[b];
    const int64_t stepB = kernels::latticeSteps(v.faceDims[b]).stride[b];
    double* out = t->u0.at[b];
    int64_t first[kTraceBatch], shift[kTraceBatch];
    if (a != 3 && b != a) {
      for (int s = 0; s < count; ++s) {
        const int face[3] = {i[s], t->j, t->k};
        first[s] = kernels::faceMeanFirst(v, a, b, face, &shift[s]);
      }
      for (int s = 0; s < count; ++s) out[s] = kernels::faceMean(u + first[s], stepB, shift[s]);
      continue;
    }
    for (int s = 0; s < count; ++s) {
      const int at[3] = {i[s], t->j, t->k};
      first[s] = kernels::latticeIndex(v.faceDims[b], at);
    }
    if (a == 3) {
      for (int s = 0; s < count; ++s) out[s] = kernels::cellMean(u + first[s], stepB);
    } else {
      for (int s = 0; s < count; ++s) out[s] = u[first[s]];
    }
  }
}

VP_ISA_CLONES
void velocityAtPoints(const kernels::MacVelocityView& view, const PointBatch& points, PointBatch* out) {
  const kernels::MacVelocityView v = view;
  const int count = points.count;
  out->count = count;
  SpanBatch spans[2];  // per lattice: 0 cell-centred, 1 face-centred
  for (int lattice = 0; lattice < 2; ++lattice) {
    double g[3][kTraceBatch];
    int samples[3];
    for (int d = 0; d < 3; ++d) {
      samples[d] = kernels::velocityLatticeSamples(v, d, lattice);
      for (int s = 0; s < count; ++s) g[d][s] = kernels::velocityLatticeCoordinate(v, d, points.at[d][s], lattice);
    }
    spansAt(g, count, samples, &spans[lattice]);
  }
  // kernels::velocityComponent, stage by stage: the stencil's first index, then the samples.
  for (int a = 0; a < 3; ++a) {
    const kernels::LatticeSteps st = kernels::latticeSteps(v.faceDims[a]);
    const SpanBatch& x = spans[a == 0];
    const SpanBatch& y = spans[a == 1];
    const SpanBatch& z = spans[a == 2];
    int64_t index[kTraceBatch];
    stencilIndices(x, y, z, st.stride, count, index);
    trilinearBatch(v.u[a], st.step, index, x.weight[0], y.weight[1], z.weight[2], count, out->at[a]);
  }
}

VP_ISA_CLONES
void traceBatch(const kernels::MacVelocityView& view, const TraceStarts& t, double dt, int latticeAxis,
                    PointBatch* traced) {
  const kernels::MacVelocityView v = view;
  const int count = t.count;
  PointBatch mid;
  mid.count = count;
  for (int s = 0; s < count; ++s) {
    double x[3], u0[3], m[3];
    for (int d = 0; d < 3; ++d) x[d] = t.x.at[d][s], u0[d] = t.u0.at[d][s];
    kernels::traceMidpoint(x, u0, dt, m);
    for (int d = 0; d < 3; ++d) mid.at[d][s] = m[d];
  }
  PointBatch uMid;
  velocityAtPoints(v, mid, &uMid);
  traced->count = count;
  for (int s = 0; s < count; ++s) {
    double x[3], u[3], end[3], g[3];
    for (int d = 0; d < 3; ++d) x[d] = t.x.at[d][s], u[d] = uMid.at[d][s];
    kernels::traceEnd(x, u, dt, end);
    kernels::latticeCoordinate(v, latticeAxis, end, g);
    for (int d = 0; d < 3; ++d) traced->at[d][s] = g[d];
  }
}

VP_ISA_CLONES
void sampleAtPoints(const double* values, const int dims[3], const PointBatch& at, double* out, double* lo,
                    double* hi) {
  SpanBatch spans;
  spansAt(at.at, at.count, dims, &spans);
  const kernels::LatticeSteps st = kernels::latticeSteps(dims);
  int64_t index[kTraceBatch];
  stencilIndices(spans, spans, spans, st.stride, at.count, index);
  trilinearBatch(values, st.step, index, spans.weight[0], spans.weight[1], spans.weight[2], at.count, out, lo, hi);
}

VP_ISA_CLONES
void sampleConnectedAtPoints(const double* values, const int dims[3], const PointBatch& at, const uint8_t* faces,
                             const uint8_t* blockOpen, double* out, double* lo, double* hi) {
  SpanBatch spans;
  spansAt(at.at, at.count, dims, &spans);
  const kernels::LatticeSteps st = kernels::latticeSteps(dims);
  const Eigen::Vector3i lattice(dims[0], dims[1], dims[2]);
  int64_t index[kTraceBatch];
  stencilIndices(spans, spans, spans, st.stride, at.count, index);
  // Every stencil as if its block were open, then the others sampled through their open faces.
  trilinearBatch(values, st.step, index, spans.weight[0], spans.weight[1], spans.weight[2], at.count, out, lo, hi);
  for (int s = 0; s < at.count; ++s) {
    if (blockOpen[index[s]]) continue;
    SampleRange range;
    out[s] = connectedTrilinearSample(values, lattice, Eigen::Vector3d(at.at[0][s], at.at[1][s], at.at[2][s]), faces,
                                      blockOpen, lo != nullptr ? &range : nullptr);
    if (lo != nullptr) lo[s] = range.lo, hi[s] = range.hi;
  }
}

}  // namespace vp
