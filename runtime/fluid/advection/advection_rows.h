// The CPU's way of running the advection kernels (gpu_kernels/advection_kernels.h): samples of
// one lattice row in batches of up to kTraceBatch, each kernel stage run over the whole batch
// before the next (positions, midpoints, stencil spans, gathers, interpolation). Per sample the
// stages form one long dependent chain of loads and conversions; across a batch they are
// independent, so the arithmetic loops vectorize and the gathers of many samples overlap.
// The values are exactly those of the per-sample kernels (the same operations in the same
// order; fluid_advection_rows_test.cpp holds them to it).
#pragma once

#include <cstdint>

#include "fluid/mac_grid.h"
#include "gpu_kernels/advection_kernels.h"

namespace vp {

constexpr int kTraceBatch = 64;

// The kernels' view of a grid's velocity.
kernels::MacVelocityView macVelocityView(const MacGrid& grid);

// Points of one batch: count samples, coordinates per axis.
struct PointBatch {
  int count = 0;
  double at[3][kTraceBatch];
};

// Samples of one row of a-faces (a = 3: cells) at positions `i` of row (j, k), with the velocity
// where they sit: the start of their traces.
struct TraceStarts {
  int axis = 0;
  int j = 0, k = 0;
  int count = 0;
  int i[kTraceBatch];
  PointBatch x;   // the samples' positions
  PointBatch u0;  // the velocity there
};

// Fills the positions and starting velocities of `starts` (axis, j, k, count and i set): a face
// has its own component (from the velocity array) and the mean of the four neighbouring faces
// for the other two; a cell the mean of its two faces per axis.
void fillTraceStarts(const kernels::MacVelocityView& v, TraceStarts* starts);

// The velocity at every point of `points`.
void velocityAtPoints(const kernels::MacVelocityView& v, const PointBatch& points, PointBatch* out);

// The midpoint-rule trace of every start over dt (negative: forward in time), as coordinates of
// the lattice of `latticeAxis`'s faces (3: cells).
void traceBatch(const kernels::MacVelocityView& v, const TraceStarts& starts, double dt, int latticeAxis,
                    PointBatch* traced);

// Trilinear samples of `values` (a lattice with `dims`) at every lattice coordinate of `at`;
// lo/hi (optional, together) receive the range of the 8 samples each used.
void sampleAtPoints(const double* values, const int dims[3], const PointBatch& at, double* out, double* lo = nullptr,
                    double* hi = nullptr);

// sampleAtPoints through open faces only (grid_sampling.h: connectedTrilinearSample, with its
// faces and blockOpen masks): a block with every inner face open interpolates as usual.
void sampleConnectedAtPoints(const double* values, const int dims[3], const PointBatch& at, const uint8_t* faces,
                             const uint8_t* blockOpen, double* out, double* lo, double* hi);

}  // namespace vp
