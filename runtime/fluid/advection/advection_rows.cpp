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

VP_ISA_CLONES
void fillTraceStarts(const kernels::MacVelocityView& view, TraceStarts* t) {
  const kernels::MacVelocityView v = view;
  const int a = t->axis, count = t->count;
  t->x.count = t->u0.count = count;
  for (int s = 0; s < count; ++s) {
    const int at[3] = {t->i[s], t->j, t->k};
    double x[3], u0[3];
    kernels::sampleCentre(v, a, at, x);
    kernels::velocityAtSample(v, a, at, u0);
    for (int d = 0; d < 3; ++d) t->x.at[d][s] = x[d], t->u0.at[d][s] = u0[d];
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
    for (int s = 0; s < count; ++s)
      index[s] = x.base[0][s] * st.stride[0] + y.base[1][s] * st.stride[1] + z.base[2][s] * st.stride[2];
    const double* u = v.u[a];
    double* result = out->at[a];
    for (int s = 0; s < count; ++s)
      result[s] = kernels::trilinear(u + index[s], st.step, x.weight[0][s], y.weight[1][s], z.weight[2][s]);
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
  for (int s = 0; s < at.count; ++s) {
    const int64_t index =
        spans.base[0][s] * st.stride[0] + spans.base[1][s] * st.stride[1] + spans.base[2][s] * st.stride[2];
    const double* p = values + index;
    if (lo != nullptr) {
      out[s] = kernels::trilinear(p, st.step, spans.weight[0][s], spans.weight[1][s], spans.weight[2][s], &lo[s],
                                  &hi[s]);
    } else {
      out[s] = kernels::trilinear(p, st.step, spans.weight[0][s], spans.weight[1][s], spans.weight[2][s]);
    }
  }
}

VP_ISA_CLONES
void sampleConnectedAtPoints(const double* values, const int dims[3], const PointBatch& at, const uint8_t* faces,
                             const uint8_t* blockOpen, double* out, double* lo, double* hi) {
  SpanBatch spans;
  spansAt(at.at, at.count, dims, &spans);
  const kernels::LatticeSteps st = kernels::latticeSteps(dims);
  const Eigen::Vector3i lattice(dims[0], dims[1], dims[2]);
  for (int s = 0; s < at.count; ++s) {
    const int64_t index =
        spans.base[0][s] * st.stride[0] + spans.base[1][s] * st.stride[1] + spans.base[2][s] * st.stride[2];
    if (blockOpen[index]) {
      out[s] = kernels::trilinear(values + index, st.step, spans.weight[0][s], spans.weight[1][s], spans.weight[2][s],
                                  lo != nullptr ? &lo[s] : nullptr, lo != nullptr ? &hi[s] : nullptr);
      continue;
    }
    SampleRange range;
    out[s] = connectedTrilinearSample(values, lattice, Eigen::Vector3d(at.at[0][s], at.at[1][s], at.at[2][s]), faces,
                                      blockOpen, lo != nullptr ? &range : nullptr);
    if (lo != nullptr) lo[s] = range.lo, hi[s] = range.hi;
  }
}

}  // namespace vp
