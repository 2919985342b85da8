// Semi-Lagrangian and MacCormack advection on the MAC grid (see advection.h).
#include "fluid/advection/advection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel_for.h"
#include "fluid/advection/advection_rows.h"
#include "fluid/advection/grid_sampling.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "gpu_kernels/level_set_kernels.h"
#include "gpu_kernels/scalar_advection_kernels.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 8;  // x-lines per parallel chunk

int64_t rowCount(const Eigen::Vector3i& d) { return static_cast<int64_t>(d.y()) * d.z(); }

// Runs body(i, j, k, index) over the samples of rows [rowBegin, rowEnd) of a lattice with
// dims d, in order.
template <class Body>
void forEachSampleInRows(const Eigen::Vector3i& d, int64_t rowBegin, int64_t rowEnd, const Body& body) {
  for (int64_t row = rowBegin; row < rowEnd; ++row) {
    const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
    size_t index = static_cast<size_t>(row) * static_cast<size_t>(d.x());
    for (int i = 0; i < d.x(); ++i, ++index) body(i, j, k, index);
  }
}

template <class Body>
void forEachSample(TaskSystem& tasks, const Eigen::Vector3i& d, const Body& body) {
  parallelFor(tasks, rowCount(d), kRowGrain,
              [&](int64_t begin, int64_t end) { forEachSampleInRows(d, begin, end, body); });
}

// Writes a batch's values (one per sample) to their samples' entries of a row's array.
void scatterBatch(const TraceStarts& batch, const double* values, double* row) {
  for (int s = 0; s < batch.count; ++s) row[batch.i[s]] = values[s];
}

// Adds a pass over the rows of a lattice with dims d: run(rows) for chunks of rows.
template <class Run>
void addRowPass(SlabPasses& passes, int target, const Eigen::Vector3i& d, const Run& run) {
  if (d.x() <= 0) return;
  passes.addParallel(rowCount(d), d.x(), kRowGrain,
                     [run, target, d](int64_t begin, int64_t end) { run(AdvectionRows{target, d, begin, end}); });
}

// Runs the samples of rows [rowBegin, rowEnd) of a lattice: those with active(index) in
// batches of one row's samples (batch(samples, index of the row's first sample); samples has
// i, j, k and count set), the others one by one (inactive(index)).
template <class Active, class Inactive, class Batch>
void forEachSampleBatch(const AdvectionRows& rows, int axis, const Active& active, const Inactive& inactive,
                        const Batch& batch) {
  const Eigen::Vector3i& d = rows.dims;
  TraceStarts samples;
  samples.axis = axis;
  for (int64_t row = rows.rowBegin; row < rows.rowEnd; ++row) {
    samples.j = static_cast<int>(row % d.y());
    samples.k = static_cast<int>(row / d.y());
    const size_t rowStart = static_cast<size_t>(row) * static_cast<size_t>(d.x());
    for (int i0 = 0; i0 < d.x(); i0 += kTraceBatch) {
      samples.count = 0;
      for (int i = i0, end = std::min(i0 + kTraceBatch, d.x()); i < end; ++i) {
        if (active(rowStart + i)) samples.i[samples.count++] = i;
        else inactive(rowStart + i);
      }
      if (samples.count > 0) batch(samples, rowStart);
    }
  }
}

// forEachSampleBatch over the samples of a-faces (a = 3: cells) with their trace starts filled.
template <class Traced, class Untraced, class Batch>
void forEachTraceBatch(const kernels::MacVelocityView& v, const AdvectionRows& rows, int axis, const Traced& traced,
                       const Untraced& untraced, const Batch& batch) {
  forEachSampleBatch(rows, axis, traced, untraced, [&](TraceStarts& starts, size_t rowStart) {
    fillTraceStarts(v, &starts);
    batch(starts, rowStart);
  });
}

void latticeDims(const Eigen::Vector3i& d, int (&out)[3]) {
  for (int e = 0; e < 3; ++e) out[e] = d[e];
}

using kernels::ScalarCellRules;  // gpu_kernels/scalar_advection_kernels.h

// Back-traces kept from the forward pass for the correction: stored at, and loaded from, the
// entries of a row's array (traces) at the samples' positions.
void storeTraces(const PointBatch& at, const TraceStarts& samples, Eigen::Vector3d* traces) {
  for (int s = 0; s < samples.count; ++s)
    traces[samples.i[s]] = Eigen::Vector3d(at.at[0][s], at.at[1][s], at.at[2][s]);
}
void loadTraces(const TraceStarts& samples, const Eigen::Vector3d* traces, PointBatch* at) {
  at->count = samples.count;
  for (int s = 0; s < samples.count; ++s)
    for (int d = 0; d < 3; ++d) at->at[d][s] = traces[samples.i[s]][d];
}

// Where MacCormack's backward step samples: each sample's back-trace reflected through it
// (kernels::reflectThrough), from the row's kept traces.
void aheadOfTraces(const TraceStarts& samples, const Eigen::Vector3d* traces, PointBatch* ahead) {
  ahead->count = samples.count;
  for (int s = 0; s < samples.count; ++s) {
    const int at[3] = {samples.i[s], samples.j, samples.k};
    double g[3];
    kernels::reflectThrough(at, traces[samples.i[s]].data(), g);
    for (int d = 0; d < 3; ++d) ahead->at[d][s] = g[d];
  }
}

// The entries of the workspace's trace array: a back-trace per face of the largest face
// lattice, which also holds one per cell, so velocities and scalars share it unresized.
size_t traceEntries(const MacGrid& grid) {
  size_t n = 0;
  for (int a = 0; a < 3; ++a) n = std::max(n, grid.velocity[a].size());
  return n;
}

// rules.sample at the points of `at` (the batch's cells' traces), in a batch; lo/hi (optional)
// the ranges of the samples used.
void sampleCells(const ScalarCellRules& rules, const double* values, const PointBatch& at, double* out, double* lo,
                 double* hi) {
  if (rules.faces != nullptr)
    sampleConnectedAtPoints(values, rules.dims, at, rules.faces, rules.blockOpen, out, lo, hi);
  else
    sampleAtPoints(values, rules.dims, at, out, lo, hi);
}

ScalarCellRules scalarCellRules(const AdvectionRows& slab, const CellOpenFaces* openFaces,
                                const Array<double>& solidValues, double keepBeyond,
                                const AdvectionWorkspace& work) {
  ScalarCellRules rules;
  rules.faces = openFaces != nullptr ? openFaces->faces.data() : nullptr;
  rules.blockOpen = openFaces != nullptr ? openFaces->blockOpen.data() : nullptr;
  rules.kept = keepBeyond > 0.0 ? work.kept.data() : nullptr;
  rules.solidValue = solidValues.empty() ? nullptr : &solidValues[static_cast<size_t>(slab.target)];
  latticeDims(slab.dims, rules.dims);
  return rules;
}

// kernels::openSideOutflow of a grid's velocity.
double openSideOutflow(const MacGrid& grid, const double* values, double dt) {
  const double* const velocity[3] = {grid.velocity[0].data(), grid.velocity[1].data(), grid.velocity[2].data()};
  return kernels::openSideOutflow(grid.layout(), velocity, values, dt, grid.spec.h);
}

// How far (metres) a point of the cell-centred lattice lies beyond the domain's Open sides,
// counting only the axes whose Open side it passed; -infinity inside the domain or beyond Wall
// sides only. The domain spans lattice coordinates [-1/2, n - 1/2] per axis.
double distanceBeyondOpenSides(const MacGrid& grid, const Eigen::Vector3d& lattice) {
  const int n[3] = {grid.spec.nx, grid.spec.ny, grid.spec.nz};
  double squared = 0.0;
  bool beyond = false;
  for (int a = 0; a < 3; ++a) {
    const double below = -0.5 - lattice[a], above = lattice[a] - (n[a] - 0.5);
    const double out = below > 0.0 && grid.side(a, false) == DomainSide::Open  ? below
                       : above > 0.0 && grid.side(a, true) == DomainSide::Open ? above
                                                                                : 0.0;
    if (out > 0.0) squared += out * out, beyond = true;
  }
  return beyond ? std::sqrt(squared) * grid.spec.h : -std::numeric_limits<double>::infinity();
}

}  // namespace

void VelocityAdvectionSlices::prepare(TaskSystem& tasks, MacGrid& grid, double dt, AdvectionScheme scheme,
                                      AdvectionWorkspace& work, const FaceSkipMask& skip) {
  grid_ = &grid;
  work_ = &work;
  dt_ = dt;
  maccormack_ = scheme == AdvectionScheme::MacCormack;
  skip_ = skip;
  passes_.reset(tasks);
  size_t largestAxis = 0;
  for (int a = 0; a < 3; ++a) {
    work.advected[a].resize(grid.velocity[a].size());
    largestAxis = std::max(largestAxis, grid.velocity[a].size());
    addRowPass(passes_, a, grid.faceDims(a), [this](const AdvectionRows& rows) { forwardPass(rows); });
    if (maccormack_)
      addRowPass(passes_, a, grid.faceDims(a), [this](const AdvectionRows& rows) { correctionPass(rows); });
  }
  // The axes take turns with the MacCormack arrays: an axis is done before the next starts.
  if (maccormack_) {
    if (work.traces.size() < traceEntries(grid)) work.traces.resize(traceEntries(grid));
    work.forward.resize(largestAxis);
    work.rangeLo.resize(largestAxis);
    work.rangeHi.resize(largestAxis);
  }
}

void VelocityAdvectionSlices::forwardPass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const int a = slab.target;
  const kernels::MacVelocityView v = macVelocityView(*grid_);
  const double* old = grid_->velocity[a].data();
  const uint8_t* marks = skip_.marks != nullptr ? skip_.marks[a].data() : nullptr;
  const uint8_t skipMark = skip_.skipMark;
  const bool maccormack = maccormack_;
  const double dt = dt_;
  double* fwd = maccormack ? work.forward.data() : work.advected[a].data();
  double* lo = maccormack ? work.rangeLo.data() : nullptr;
  double* hi = maccormack ? work.rangeHi.data() : nullptr;
  Eigen::Vector3d* traces = maccormack ? work.traces.data() : nullptr;
  int dims[3];
  latticeDims(slab.dims, dims);
  forEachTraceBatch(
      v, slab, a, [&](size_t f) { return marks == nullptr || marks[f] != skipMark; },
      [&](size_t f) {
        fwd[f] = old[f];
        if (maccormack) lo[f] = hi[f] = old[f];
      },
      [&](const TraceStarts& starts, size_t rowStart) {
        PointBatch from;
        traceBatch(v, starts, dt, a, &from);
        double value[kTraceBatch], low[kTraceBatch], high[kTraceBatch];
        sampleAtPoints(old, dims, from, value, maccormack ? low : nullptr, maccormack ? high : nullptr);
        scatterBatch(starts, value, fwd + rowStart);
        if (!maccormack) return;
        scatterBatch(starts, low, lo + rowStart);
        scatterBatch(starts, high, hi + rowStart);
        storeTraces(from, starts, traces + rowStart);
      });
}

void VelocityAdvectionSlices::correctionPass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const int a = slab.target;
  const double* old = grid_->velocity[a].data();
  const uint8_t* marks = skip_.marks != nullptr ? skip_.marks[a].data() : nullptr;
  const uint8_t skipMark = skip_.skipMark;
  const double* fwd = work.forward.data();
  const double* lo = work.rangeLo.data();
  const double* hi = work.rangeHi.data();
  const Eigen::Vector3d* traces = work.traces.data();
  double* out = work.advected[a].data();
  int dims[3];
  latticeDims(slab.dims, dims);
  forEachSampleBatch(
      slab, a, [&](size_t f) { return marks == nullptr || marks[f] != skipMark; },
      [&](size_t f) { out[f] = old[f]; },
      [&](const TraceStarts& starts, size_t rowStart) {
        PointBatch ahead;
        aheadOfTraces(starts, traces + rowStart, &ahead);
        double backAgain[kTraceBatch];
        sampleAtPoints(fwd, dims, ahead, backAgain);
        for (int s = 0; s < starts.count; ++s) {
          const size_t f = rowStart + static_cast<size_t>(starts.i[s]);
          out[f] = kernels::maccormackValue(fwd[f], old[f], backAgain[s], lo[f], hi[f]);
        }
      });
}

void VelocityAdvectionSlices::finish() {
  for (int a = 0; a < 3; ++a) grid_->velocity[a].swap(work_->advected[a]);
}

void advectVelocity(TaskSystem& tasks, MacGrid& grid, double dt, AdvectionScheme scheme, AdvectionWorkspace& work,
                    const FaceSkipMask& skip) {
  VelocityAdvectionSlices slices;
  slices.prepare(tasks, grid, dt, scheme, work, skip);
  slices.runSlice(std::numeric_limits<int64_t>::max());
  slices.finish();
}

void buildCellOpenFaces(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions, CellOpenFaces* out) {
  const MacGridSpec& s = grid.spec;
  const Eigen::Vector3i d(s.nx, s.ny, s.nz);
  const size_t cells = static_cast<size_t>(grid.cellCount());
  out->faces.resize(cells);
  out->blockOpen.resize(cells);
  forEachSample(tasks, d, [&](int i, int j, int k, size_t c) {
    uint8_t bits = 0;
    for (int a = 0; a < 3; ++a)
      for (int high = 0; high < 2; ++high) {
        Eigen::Vector3i f(i, j, k);
        f[a] += high;
        if (effectiveOpenFraction(grid, fractions, a, f.x(), f.y(), f.z()) > 0.0)
          bits |= static_cast<uint8_t>((1u << (2 * a + high)) | kCellIsFluid);
      }
    out->faces[c] = bits;
  });
  const size_t stride[3] = {1, static_cast<size_t>(s.nx), static_cast<size_t>(s.nx) * s.ny};
  forEachSample(tasks, d, [&](int i, int j, int k, size_t c) {
    const int at[3] = {i, j, k};
    uint8_t open = 1;
    for (int a = 0; a < 3 && open; ++a) {
      if (d[a] == 1) continue;  // one cell along a: no inner faces
      if (at[a] + 1 >= d[a]) {  // never the lowest cell of a block
        open = 0;
        break;
      }
      // The block's inner faces normal to a: the high faces of its 4 cells at the lower a.
      const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
      for (int q = 0; q < 4 && open; ++q) {
        const int o1 = q & 1, o2 = q >> 1;
        if ((o1 && d[b1] == 1) || (o2 && d[b2] == 1)) continue;
        if (at[b1] + o1 >= d[b1] || at[b2] + o2 >= d[b2]) {
          open = 0;
          break;
        }
        const size_t cell = c + o1 * stride[b1] + o2 * stride[b2];
        if (!(out->faces[cell] & (1u << (2 * a + 1)))) open = 0;
      }
    }
    out->blockOpen[c] = open;
  });
}

void ScalarAdvectionSlices::prepare(TaskSystem& tasks, const MacGrid& grid, double dt, AdvectionScheme scheme,
                                    Array<double>* const* fields, int fieldCount, AdvectionWorkspace& work,
                                    const CellOpenFaces* openFaces, const double* solidValues, double keepBeyond,
                                    int conservedField, int levelSetField) {
  grid_ = &grid;
  work_ = &work;
  dt_ = dt;
  maccormack_ = scheme == AdvectionScheme::MacCormack;
  fields_.clear();
  if (fieldCount > 0) fields_.assign(fields, fields + fieldCount);
  openFaces_ = openFaces;
  solidValues_.clear();
  if (solidValues != nullptr) solidValues_.assign(solidValues, solidValues + fields_.size());
  keepBeyond_ = keepBeyond;
  levelSetField_ = levelSetField;
  passes_.reset(tasks);
  if (fields_.empty()) return;
  const Eigen::Vector3i d(grid.spec.nx, grid.spec.ny, grid.spec.nz);
  const size_t cells = static_cast<size_t>(grid.cellCount());
  // The back-traces are shared by all fields (and, for MacCormack, reflected for the backward
  // step).
  if (work.traces.size() < traceEntries(grid)) work.traces.resize(traceEntries(grid));
  // Decided from the first field's old values once (trace pass): the fields are swapped as
  // they are done.
  work.kept.assign(keepBeyond > 0.0 ? cells : 0, 0);
  work.forward.resize(cells);
  work.advected[0].resize(cells);
  if (maccormack_) {
    work.rangeLo.resize(cells);
    work.rangeHi.resize(cells);
  }
  const bool conserve = conservedField >= 0 && conservedField < static_cast<int>(fields_.size());
  if (conserve) addTargetTotalPasses(conservedField);
  addRowPass(passes_, 0, d, [this](const AdvectionRows& rows) { tracePass(rows); });
  for (int which = 0; which < static_cast<int>(fields_.size()); ++which) {
    addRowPass(passes_, which, d, [this](const AdvectionRows& rows) { forwardPass(rows); });
    if (maccormack_) addRowPass(passes_, which, d, [this](const AdvectionRows& rows) { correctionPass(rows); });
    passes_.addStep([this, which] { fields_[static_cast<size_t>(which)]->swap(work_->advected[0]); });
    if (conserve && which == conservedField) addRescalePasses(which);
    if (which == levelSetField) addSheetClosingPasses(which);
  }
}

void ScalarAdvectionSlices::addSheetClosingPasses(int field) {
  const Eigen::Vector3i d(grid_->spec.nx, grid_->spec.ny, grid_->spec.nz);
  addRowPass(passes_, field, d, [this](const AdvectionRows& rows) {
    const double* phi = fields_[static_cast<size_t>(rows.target)]->data();
    const kernels::MacLayout layout = grid_->layout();
    const double* const u[3] = {grid_->velocity[0].data(), grid_->velocity[1].data(), grid_->velocity[2].data()};
    double* rise = work_->forward.data();
    const int nx = rows.dims.x(), ny = rows.dims.y();
    for (int64_t row = rows.rowBegin; row < rows.rowEnd; ++row)
      for (int i = 0; i < nx; ++i)
        rise[row * nx + i] = dt_ * kernels::sheetClosingSpeed(layout, phi, u, i, row % ny, row / ny);
  });
  addRowPass(passes_, field, d, [this](const AdvectionRows& rows) {
    double* phi = fields_[static_cast<size_t>(rows.target)]->data();
    const double* rise = work_->forward.data();
    for (int64_t c = rows.rowBegin * rows.dims.x(); c < rows.rowEnd * rows.dims.x(); ++c) phi[c] += rise[c];
  });
}

void ScalarAdvectionSlices::addRowSumPass(int field) {
  const Eigen::Vector3i d(grid_->spec.nx, grid_->spec.ny, grid_->spec.nz);
  rowSums_.resize(static_cast<size_t>(rowCount(d)));
  addRowPass(passes_, field, d, [this](const AdvectionRows& rows) {
    const double* values = fields_[static_cast<size_t>(rows.target)]->data();
    for (int64_t row = rows.rowBegin; row < rows.rowEnd; ++row)
      rowSums_[static_cast<size_t>(row)] = kernels::cellRowSum(values, rows.dims.x(), row);
  });
}

double ScalarAdvectionSlices::rowSumTotal() const {
  double total = 0.0;
  for (double s : rowSums_) total += s;
  return total;
}

void ScalarAdvectionSlices::addTargetTotalPasses(int field) {
  addRowSumPass(field);
  passes_.addStep([this, field] {
    targetTotal_ = rowSumTotal() - openSideOutflow(*grid_, fields_[static_cast<size_t>(field)]->data(), dt_);
  });
}

void ScalarAdvectionSlices::addRescalePasses(int field) {
  addRowSumPass(field);
  passes_.addStep([this] {
    const double total = rowSumTotal();
    scale_ = kernels::conservationScale(targetTotal_, total);
  });
  const Eigen::Vector3i d(grid_->spec.nx, grid_->spec.ny, grid_->spec.nz);
  addRowPass(passes_, field, d, [this](const AdvectionRows& rows) {
    double* values = fields_[static_cast<size_t>(rows.target)]->data();
    for (int64_t c = rows.rowBegin * rows.dims.x(); c < rows.rowEnd * rows.dims.x(); ++c) values[c] *= scale_;
  });
}

void ScalarAdvectionSlices::tracePass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const kernels::MacVelocityView v = macVelocityView(*grid_);
  const double* first = fields_[0]->data();
  const double keepBeyond = keepBeyond_, dt = dt_;
  Eigen::Vector3d* traces = work.traces.data();
  forEachTraceBatch(
      v, slab, 3, [&](size_t c) { return !(keepBeyond > 0.0 && std::abs(first[c]) >= keepBeyond); },
      [&](size_t c) { work.kept[c] = 1; },
      [&](const TraceStarts& starts, size_t rowStart) {
        PointBatch at;
        traceBatch(v, starts, dt, 3, &at);
        storeTraces(at, starts, traces + rowStart);
      });
}

void ScalarAdvectionSlices::forwardPass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const ScalarCellRules rules = scalarCellRules(slab, openFaces_, solidValues_, keepBeyond_, work);
  const Array<double>& old = *fields_[static_cast<size_t>(slab.target)];
  const bool maccormack = maccormack_;
  // Semi-Lagrangian: the forward result is the advected field.
  double* fwd = maccormack ? work.forward.data() : work.advected[0].data();
  double* lo = work.rangeLo.data();
  double* hi = work.rangeHi.data();
  forEachSampleBatch(
      slab, 3, [&](size_t c) { return rules.advected(c); },
      [&](size_t c) {
        fwd[c] = rules.unadvected(old.data(), static_cast<int64_t>(c));
        if (maccormack) lo[c] = hi[c] = fwd[c];
      },
      [&](const TraceStarts& cells, size_t rowStart) {
        double value[kTraceBatch], low[kTraceBatch], high[kTraceBatch];
        PointBatch back;
        loadTraces(cells, work.traces.data() + rowStart, &back);
        sampleCells(rules, old.data(), back, value, maccormack ? low : nullptr, maccormack ? high : nullptr);
        keepAirBeyondOpenSides(slab, cells, work.traces.data() + rowStart, value, maccormack ? high : nullptr);
        scatterBatch(cells, value, fwd + rowStart);
        if (!maccormack) return;
        scatterBatch(cells, low, lo + rowStart);
        scatterBatch(cells, high, hi + rowStart);
      });
}

void ScalarAdvectionSlices::correctionPass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const ScalarCellRules rules = scalarCellRules(slab, openFaces_, solidValues_, keepBeyond_, work);
  const Array<double>& old = *fields_[static_cast<size_t>(slab.target)];
  const double* fwd = work.forward.data();
  double* out = work.advected[0].data();
  forEachSampleBatch(
      slab, 3, [&](size_t c) { return rules.advected(c); }, [&](size_t c) { out[c] = fwd[c]; },
      [&](const TraceStarts& batch, size_t rowStart) {
        double backAgain[kTraceBatch], corrected[kTraceBatch];
        PointBatch ahead;
        aheadOfTraces(batch, work.traces.data() + rowStart, &ahead);
        sampleCells(rules, fwd, ahead, backAgain, nullptr, nullptr);
        for (int s = 0; s < batch.count; ++s) {
          const size_t c = rowStart + static_cast<size_t>(batch.i[s]);
          corrected[s] = kernels::maccormackClamped(fwd[c], old[c], backAgain[s], work.rangeLo[c], work.rangeHi[c]);
        }
        keepAirBeyondOpenSides(slab, batch, work.traces.data() + rowStart, corrected, nullptr);
        scatterBatch(batch, corrected, out + rowStart);
      });
}

void ScalarAdvectionSlices::keepAirBeyondOpenSides(const AdvectionRows& rows, const TraceStarts& cells,
                                                   const Eigen::Vector3d* traces, double* values,
                                                   double* rangeHigh) const {
  if (rows.target != levelSetField_) return;
  for (int s = 0; s < cells.count; ++s) {
    values[s] = std::max(values[s], distanceBeyondOpenSides(*grid_, traces[cells.i[s]]));
    // MacCormack's correction is clamped to this range: it must not take the air back.
    if (rangeHigh != nullptr) rangeHigh[s] = std::max(rangeHigh[s], values[s]);
  }
}

void advectCellScalars(TaskSystem& tasks, const MacGrid& grid, double dt, AdvectionScheme scheme,
                       Array<double>* const* fields, int fieldCount, AdvectionWorkspace& work,
                       const CellOpenFaces* openFaces, const double* solidValues, double keepBeyond,
                       int conservedField, int levelSetField) {
  ScalarAdvectionSlices slices;
  slices.prepare(tasks, grid, dt, scheme, fields, fieldCount, work, openFaces, solidValues, keepBeyond,
                 conservedField, levelSetField);
  slices.runSlice(std::numeric_limits<int64_t>::max());
}

}  // namespace vp
