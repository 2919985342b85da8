// Batched advection stages over the kernels of gpu_kernels/advection_kernels.h (see
// advection_rows.h).
#include "fluid/advection/advection_rows.h"

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

void fillTraceStarts(const kernels::MacVelocityView& v, TraceStarts* t) {
  t->x.count = t->u0.count = t->count;
  for (int s = 0; s < t->count; ++s) {
    const int at[3] = {t->i[s], t->j, t->k};
    double x[3], u0[3];
    kernels::sampleCentre(v, t->axis, at, x);
    kernels::velocityAtSample(v, t->axis, at, u0);
    for (int d = 0; d < 3; ++d) t->x.at[d][s] = x[d], t->u0.at[d][s] = u0[d];
  }
}

void velocityAtPoints(const kernels::MacVelocityView& v, const PointBatch& points, PointBatch* out) {
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
  for (int a = 0; a < 3; ++a) {
    double* result = out->at[a];
    for (int s = 0; s < count; ++s) {
      int base[2][3];
      double weight[2][3];
      for (int lattice = 0; lattice < 2; ++lattice)
        for (int d = 0; d < 3; ++d) {
          base[lattice][d] = spans[lattice].base[d][s];
          weight[lattice][d] = spans[lattice].weight[d][s];
        }
      result[s] = kernels::velocityComponent(v, a, base, weight);
    }
  }
}

void traceToLattice(const kernels::MacVelocityView& v, const TraceStarts& t, double dt, int latticeAxis,
                    PointBatch* traced) {
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

}  // namespace vp
