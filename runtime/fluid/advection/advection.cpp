// Semi-Lagrangian and MacCormack advection on the MAC grid (see advection.h).
#include "fluid/advection/advection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel_for.h"
#include "fluid/advection/grid_sampling.h"
#include "fluid/pressure/cut_cell_poisson.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 8;  // x-lines per parallel chunk

// The grid's velocity as a field that can be sampled anywhere, with the per-axis lattice data
// computed once instead of per sample (sampling is most of advection's time).
struct VelocityField {
  const double* u[3];
  Eigen::Vector3i dims[3];
  Eigen::Vector3d origin;
  double invH;

  explicit VelocityField(const MacGrid& g) : origin(g.spec.origin), invH(1.0 / g.spec.h) {
    for (int a = 0; a < 3; ++a) u[a] = g.velocity[a].data(), dims[a] = g.faceDims(a);
  }
  // The three components at x. Each axis has two lattices (face-centred along the component's
  // own axis, cell-centred along the others), so the clamp/floor/weight work is done once per
  // axis and lattice and shared by the components: a third of what three independent
  // trilinear samples would do.
  Eigen::Vector3d sample(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d l = (x - origin) * invH - Eigen::Vector3d::Constant(0.5);
    int base[2][3];
    double weight[2][3];
    for (int d = 0; d < 3; ++d) {
      const int cells = dims[d][d] - 1;
      for (int lattice = 0; lattice < 2; ++lattice) {  // 0: cell-centred, 1: face-centred
        const int samples = cells + lattice;
        double g = l[d] + 0.5 * lattice;
        if (!(g >= 0.0)) g = 0.0;  // also NaN
        g = std::min(g, static_cast<double>(samples - 1));
        const int b = std::min(static_cast<int>(g), std::max(samples - 2, 0));
        base[lattice][d] = b;
        weight[lattice][d] = samples > 1 ? g - b : 0.0;
      }
    }
    Eigen::Vector3d v;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3i& n = dims[a];
      int b[3];
      double w[3];
      for (int d = 0; d < 3; ++d) b[d] = base[d == a][d], w[d] = weight[d == a][d];
      const int64_t sy = n.x(), sz = int64_t(n.x()) * n.y();
      const int64_t step[3] = {n.x() > 1 ? 1 : 0, n.y() > 1 ? sy : 0, n.z() > 1 ? sz : 0};
      const double* p = u[a] + b[0] + b[1] * sy + b[2] * sz;
      const double x00 = p[0] + w[0] * (p[step[0]] - p[0]);
      const double x10 = p[step[1]] + w[0] * (p[step[0] + step[1]] - p[step[1]]);
      const double x01 = p[step[2]] + w[0] * (p[step[0] + step[2]] - p[step[2]]);
      const double x11 = p[step[1] + step[2]] + w[0] * (p[step[0] + step[1] + step[2]] - p[step[1] + step[2]]);
      const double y0 = x00 + w[1] * (x10 - x00), y1 = x01 + w[1] * (x11 - x01);
      v[a] = y0 + w[2] * (y1 - y0);
    }
    return v;
  }
  // Component b (!= a) at the centre of a-face (i, j, k): the mean of the four b-faces
  // around it (what trilinear sampling gives there, without its cost); at the domain's
  // a-sides the face has cells on one side only and takes that side's pair.
  double otherComponentAtFace(int a, int b, int i, int j, int k) const {
    const Eigen::Vector3i& d = dims[b];
    const int64_t stride[3] = {1, d.x(), int64_t(d.x()) * d.y()};
    const Eigen::Vector3i cell(i, j, k);
    const int cellsA = d[a];  // b-faces have as many entries along a as there are cells
    const int lo = std::max(cell[a] - 1, 0), hi = std::min(cell[a], cellsA - 1);
    Eigen::Vector3i c = cell;
    c[a] = lo;
    const int64_t base = c.x() * stride[0] + c.y() * stride[1] + c.z() * stride[2];
    const int64_t shift = (hi - lo) * stride[a];
    const double* p = u[b] + base;
    return 0.25 * (p[0] + p[stride[b]] + p[shift] + p[shift + stride[b]]);
  }
  Eigen::Vector3d atFace(int a, int i, int j, int k, double own) const {
    Eigen::Vector3d v;
    v[a] = own;
    v[(a + 1) % 3] = otherComponentAtFace(a, (a + 1) % 3, i, j, k);
    v[(a + 2) % 3] = otherComponentAtFace(a, (a + 2) % 3, i, j, k);
    return v;
  }
};

// Midpoint-rule trace over `dt` (negative dt traces forward in time) from x, where the
// velocity is u0.
Eigen::Vector3d trace(const VelocityField& field, const Eigen::Vector3d& x, const Eigen::Vector3d& u0, double dt) {
  return x - dt * field.sample(x - 0.5 * dt * u0);
}

// Lattice coordinate of world point x for the samples of a-faces (a = 3: cell centres).
Eigen::Vector3d latticeCoordinate(const MacGridSpec& s, const Eigen::Vector3d& x, int a) {
  Eigen::Vector3d l = (x - s.origin) / s.h - Eigen::Vector3d::Constant(0.5);
  if (a < 3) l[a] += 0.5;
  return l;
}

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

template <class Body>
void forEachSampleIn(const AdvectionRows& rows, const Body& body) {
  forEachSampleInRows(rows.dims, rows.rowBegin, rows.rowEnd, body);
}

// Adds a pass over the rows of a lattice with dims d: run(rows) for chunks of rows.
template <class Run>
void addRowPass(SlabPasses& passes, int target, const Eigen::Vector3i& d, const Run& run) {
  if (d.x() <= 0) return;
  passes.addParallel(rowCount(d), d.x(), kRowGrain,
                     [run, target, d](int64_t begin, int64_t end) { run(AdvectionRows{target, d, begin, end}); });
}

// What both velocity passes read for the faces of one axis.
struct VelocityAxisInputs {
  const MacGrid& grid;
  const VelocityField field;
  const int axis;
  const std::vector<double>& old;
  const uint8_t* marks;  // null: no face is skipped
  const uint8_t skipMark;

  VelocityAxisInputs(const MacGrid& g, const FaceSkipMask& skip, int a)
      : grid(g), field(g), axis(a), old(g.velocity[a]),
        marks(skip.marks != nullptr ? skip.marks[a].data() : nullptr), skipMark(skip.skipMark) {}
  bool skipped(size_t f) const { return marks != nullptr && marks[f] == skipMark; }
  // Where face f = (i, j, k) traces to over dt (negative: forward in time), as a coordinate of
  // the axis' face lattice.
  Eigen::Vector3d tracedFrom(int i, int j, int k, size_t f, double dt) const {
    const Eigen::Vector3d x = grid.faceCentre(axis, i, j, k);
    return latticeCoordinate(grid.spec, trace(field, x, field.atFace(axis, i, j, k, old[f]), dt), axis);
  }
};

// What a scalar pass asks of a cell besides its trace: is it solid (no open face: it is not
// advected and holds the solid value), does it keep its value (keepBeyond); and how the old
// field is sampled (through open faces only, or plainly).
struct ScalarCellRules {
  const uint8_t* faces;  // null: no open-face masks
  const uint8_t* blockOpen;
  const uint8_t* kept;  // null: keepBeyond off
  const double* solidValue;  // null: solid cells keep their values
  Eigen::Vector3i dims;

  bool solid(size_t c) const { return faces != nullptr && !(faces[c] & kCellIsFluid); }
  bool keeps(size_t c) const { return kept != nullptr && kept[c]; }
  double solidResult(const std::vector<double>& old, size_t c) const {
    return solidValue != nullptr ? *solidValue : old[c];
  }
  double sample(const double* values, const Eigen::Vector3d& at, SampleRange* range) const {
    return faces != nullptr ? connectedTrilinearSample(values, dims, at, faces, blockOpen, range)
                            : trilinearSample(values, dims, at, range);
  }
};

ScalarCellRules scalarCellRules(const AdvectionRows& slab, const CellOpenFaces* openFaces,
                                const std::vector<double>& solidValues, double keepBeyond,
                                const AdvectionWorkspace& work) {
  ScalarCellRules rules;
  rules.faces = openFaces != nullptr ? openFaces->faces.data() : nullptr;
  rules.blockOpen = openFaces != nullptr ? openFaces->blockOpen.data() : nullptr;
  rules.kept = keepBeyond > 0.0 ? work.kept.data() : nullptr;
  rules.solidValue = solidValues.empty() ? nullptr : &solidValues[static_cast<size_t>(slab.target)];
  rules.dims = slab.dims;
  return rules;
}

// What the outward velocities of the open domain sides carry out of their boundary cells'
// values over dt, in value x cells (a face passes u dt h^2 of volume, a cell holds h^3).
double openSideOutflow(const MacGrid& grid, const double* values, double dt) {
  const MacGridSpec& s = grid.spec;
  const int n[3] = {s.nx, s.ny, s.nz};
  double out = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int high = 0; high < 2; ++high) {
      if (grid.side(a, high != 0) != DomainSide::Open) continue;
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      for (int q = 0; q < n[c]; ++q)
        for (int p = 0; p < n[b]; ++p) {
          int face[3], cell[3];
          face[a] = high ? n[a] : 0;
          cell[a] = high ? n[a] - 1 : 0;
          face[b] = cell[b] = p;
          face[c] = cell[c] = q;
          const double u = grid.velocity[a][grid.faceIndex(a, face[0], face[1], face[2])];
          const double outward = high ? u : -u;
          if (outward > 0.0) out += outward * dt / s.h * values[grid.cellIndex(cell[0], cell[1], cell[2])];
        }
    }
  return out;
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
    work.forward.resize(largestAxis);
    work.rangeLo.resize(largestAxis);
    work.rangeHi.resize(largestAxis);
  }
}

void VelocityAdvectionSlices::forwardPass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const VelocityAxisInputs in(*grid_, skip_, slab.target);
  const bool maccormack = maccormack_;
  const double dt = dt_;
  double* fwd = maccormack ? work.forward.data() : work.advected[slab.target].data();
  forEachSampleIn(slab, [&](int i, int j, int k, size_t f) {
    if (in.skipped(f)) {
      fwd[f] = in.old[f];
      if (maccormack) work.rangeLo[f] = work.rangeHi[f] = in.old[f];
      return;
    }
    SampleRange range;
    fwd[f] = trilinearSample(in.old.data(), slab.dims, in.tracedFrom(i, j, k, f, dt), maccormack ? &range : nullptr);
    if (maccormack) work.rangeLo[f] = range.lo, work.rangeHi[f] = range.hi;
  });
}

void VelocityAdvectionSlices::correctionPass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const VelocityAxisInputs in(*grid_, skip_, slab.target);
  const double dt = dt_;
  const std::vector<double>& fwd = work.forward;
  std::vector<double>& out = work.advected[slab.target];
  forEachSampleIn(slab, [&](int i, int j, int k, size_t f) {
    if (in.skipped(f)) {
      out[f] = in.old[f];
      return;
    }
    const double backAgain = trilinearSample(fwd.data(), slab.dims, in.tracedFrom(i, j, k, f, -dt));
    // Where the correction leaves the range of the samples the forward step read, the
    // semi-Lagrangian value is kept (Selle et al.'s own limiter) rather than the correction
    // clamped to the range: clamped, every such face took the extreme of its stencil, which
    // near a free surface (extrapolated air velocities in the stencil) pumped energy in step
    // after step; a stirred tank then ran away after 5 to 8 s (fluid_paddle_buoy_test.cpp).
    const double corrected = fwd[f] + 0.5 * (in.old[f] - backAgain);
    out[f] = corrected >= work.rangeLo[f] && corrected <= work.rangeHi[f] ? corrected : fwd[f];
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
                                    std::vector<double>* const* fields, int fieldCount, AdvectionWorkspace& work,
                                    const CellOpenFaces* openFaces, const double* solidValues, double keepBeyond,
                                    int conservedField) {
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
  passes_.reset(tasks);
  if (fields_.empty()) return;
  const Eigen::Vector3i d(grid.spec.nx, grid.spec.ny, grid.spec.nz);
  const size_t cells = static_cast<size_t>(grid.cellCount());
  // Both traces are shared by all fields: back (where the value comes from) and, for
  // MacCormack, ahead (where the backward step samples the forward result).
  work.cellTrace.resize(maccormack_ ? 2 * cells : cells);
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
  }
}

void ScalarAdvectionSlices::addRowSumPass(int field) {
  const Eigen::Vector3i d(grid_->spec.nx, grid_->spec.ny, grid_->spec.nz);
  rowSums_.resize(static_cast<size_t>(rowCount(d)));
  addRowPass(passes_, field, d, [this](const AdvectionRows& rows) {
    const double* values = fields_[static_cast<size_t>(rows.target)]->data();
    for (int64_t row = rows.rowBegin; row < rows.rowEnd; ++row) {
      const double* v = values + row * rows.dims.x();
      double sum = 0.0;
      for (int i = 0; i < rows.dims.x(); ++i) sum += v[i];
      rowSums_[static_cast<size_t>(row)] = sum;
    }
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
    scale_ = total > 0.0 ? std::max(targetTotal_, 0.0) / total : 1.0;
  });
  const Eigen::Vector3i d(grid_->spec.nx, grid_->spec.ny, grid_->spec.nz);
  addRowPass(passes_, field, d, [this](const AdvectionRows& rows) {
    double* values = fields_[static_cast<size_t>(rows.target)]->data();
    for (int64_t c = rows.rowBegin * rows.dims.x(); c < rows.rowEnd * rows.dims.x(); ++c) values[c] *= scale_;
  });
}

void ScalarAdvectionSlices::tracePass(const AdvectionRows& slab) {
  const MacGrid& grid = *grid_;
  AdvectionWorkspace& work = *work_;
  const size_t cells = static_cast<size_t>(grid.cellCount());
  const VelocityField field(grid);
  const double* first = fields_[0]->data();
  const double keepBeyond = keepBeyond_, dt = dt_;
  const bool maccormack = maccormack_;
  forEachSampleIn(slab, [&](int i, int j, int k, size_t c) {
    if (keepBeyond > 0.0 && std::abs(first[c]) >= keepBeyond) {
      work.kept[c] = 1;
      return;
    }
    const Eigen::Vector3d x = grid.cellCentre(i, j, k);
    const Eigen::Vector3d u = grid.cellVelocity(i, j, k);
    work.cellTrace[c] = latticeCoordinate(grid.spec, trace(field, x, u, dt), 3);
    if (maccormack) work.cellTrace[cells + c] = latticeCoordinate(grid.spec, trace(field, x, u, -dt), 3);
  });
}

void ScalarAdvectionSlices::forwardPass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const ScalarCellRules rules = scalarCellRules(slab, openFaces_, solidValues_, keepBeyond_, work);
  const std::vector<double>& old = *fields_[static_cast<size_t>(slab.target)];
  const bool maccormack = maccormack_;
  // Semi-Lagrangian: the forward result is the advected field.
  double* fwd = maccormack ? work.forward.data() : work.advected[0].data();
  forEachSampleIn(slab, [&](int, int, int, size_t c) {
    if (rules.solid(c) || rules.keeps(c)) {
      fwd[c] = rules.solid(c) ? rules.solidResult(old, c) : old[c];
      if (maccormack) work.rangeLo[c] = work.rangeHi[c] = fwd[c];
      return;
    }
    SampleRange range;
    fwd[c] = rules.sample(old.data(), work.cellTrace[c], maccormack ? &range : nullptr);
    if (maccormack) work.rangeLo[c] = range.lo, work.rangeHi[c] = range.hi;
  });
}

void ScalarAdvectionSlices::correctionPass(const AdvectionRows& slab) {
  AdvectionWorkspace& work = *work_;
  const ScalarCellRules rules = scalarCellRules(slab, openFaces_, solidValues_, keepBeyond_, work);
  const std::vector<double>& old = *fields_[static_cast<size_t>(slab.target)];
  const size_t cells = static_cast<size_t>(grid_->cellCount());
  std::vector<double>& out = work.advected[0];
  forEachSampleIn(slab, [&](int, int, int, size_t c) {
    if (rules.solid(c) || rules.keeps(c)) {
      out[c] = work.forward[c];
      return;
    }
    const double backAgain = rules.sample(work.forward.data(), work.cellTrace[cells + c], nullptr);
    out[c] = std::clamp(work.forward[c] + 0.5 * (old[c] - backAgain), work.rangeLo[c], work.rangeHi[c]);
  });
}

void advectCellScalars(TaskSystem& tasks, const MacGrid& grid, double dt, AdvectionScheme scheme,
                       std::vector<double>* const* fields, int fieldCount, AdvectionWorkspace& work,
                       const CellOpenFaces* openFaces, const double* solidValues, double keepBeyond,
                       int conservedField) {
  ScalarAdvectionSlices slices;
  slices.prepare(tasks, grid, dt, scheme, fields, fieldCount, work, openFaces, solidValues, keepBeyond,
                 conservedField);
  slices.runSlice(std::numeric_limits<int64_t>::max());
}

}  // namespace vp
