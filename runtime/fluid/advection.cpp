// Semi-Lagrangian and MacCormack advection on the MAC grid (see advection.h).
#include "fluid/advection.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "fluid/cut_cell_poisson.h"
#include "fluid/grid_sampling.h"

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

// Runs body(i, j, k, index) over every sample of a lattice with dims d, parallel over lines.
template <class Body>
void forEachSample(TaskSystem& tasks, const Eigen::Vector3i& d, const Body& body) {
  parallelFor(tasks, static_cast<int64_t>(d.y()) * d.z(), kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
      size_t index = static_cast<size_t>(row) * static_cast<size_t>(d.x());
      for (int i = 0; i < d.x(); ++i, ++index) body(i, j, k, index);
    }
  });
}

}  // namespace

void advectVelocity(TaskSystem& tasks, MacGrid& grid, double dt, AdvectionScheme scheme, AdvectionWorkspace& work,
                    const FaceSkipMask& skip) {
  const MacGridSpec& s = grid.spec;
  const bool maccormack = scheme == AdvectionScheme::MacCormack;
  const VelocityField field(grid);
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid.faceDims(a);
    const std::vector<double>& old = grid.velocity[a];
    const uint8_t* marks = skip.marks != nullptr ? skip.marks[a].data() : nullptr;
    auto skipped = [&](size_t f) { return marks != nullptr && marks[f] == skip.skipMark; };
    std::vector<double>& out = work.advected[a];
    out.resize(old.size());
    std::vector<double>& fwd = maccormack ? work.forward : out;
    fwd.resize(old.size());
    if (maccormack) {
      work.rangeLo.resize(old.size());
      work.rangeHi.resize(old.size());
    }
    forEachSample(tasks, d, [&](int i, int j, int k, size_t f) {
      if (skipped(f)) {
        fwd[f] = old[f];
        if (maccormack) work.rangeLo[f] = work.rangeHi[f] = old[f];
        return;
      }
      const Eigen::Vector3d x = grid.faceCentre(a, i, j, k);
      const Eigen::Vector3d back = trace(field, x, field.atFace(a, i, j, k, old[f]), dt);
      SampleRange range;
      fwd[f] = trilinearSample(old.data(), d, latticeCoordinate(s, back, a), maccormack ? &range : nullptr);
      if (maccormack) work.rangeLo[f] = range.lo, work.rangeHi[f] = range.hi;
    });
    if (!maccormack) continue;
    forEachSample(tasks, d, [&](int i, int j, int k, size_t f) {
      if (skipped(f)) {
        out[f] = old[f];
        return;
      }
      const Eigen::Vector3d x = grid.faceCentre(a, i, j, k);
      const Eigen::Vector3d ahead = trace(field, x, field.atFace(a, i, j, k, old[f]), -dt);
      const double backAgain = trilinearSample(fwd.data(), d, latticeCoordinate(s, ahead, a));
      // Where the correction leaves the range of the samples the forward step read, the
      // semi-Lagrangian value is kept (Selle et al.'s own limiter) rather than the correction
      // clamped to the range: clamped, every such face took the extreme of its stencil, which
      // near a free surface (extrapolated air velocities in the stencil) pumped energy in step
      // after step; a stirred tank then ran away after 5 to 8 s (fluid_paddle_buoy_test.cpp).
      const double corrected = fwd[f] + 0.5 * (old[f] - backAgain);
      out[f] = corrected >= work.rangeLo[f] && corrected <= work.rangeHi[f] ? corrected : fwd[f];
    });
  }
  for (int a = 0; a < 3; ++a) grid.velocity[a].swap(work.advected[a]);
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

void advectCellScalars(TaskSystem& tasks, const MacGrid& grid, double dt, AdvectionScheme scheme,
                       std::vector<double>* const* fields, int fieldCount, AdvectionWorkspace& work,
                       const CellOpenFaces* openFaces, const double* solidValues, double keepBeyond) {
  if (fieldCount <= 0) return;
  const MacGridSpec& s = grid.spec;
  const Eigen::Vector3i d(s.nx, s.ny, s.nz);
  const size_t cells = static_cast<size_t>(grid.cellCount());
  const bool maccormack = scheme == AdvectionScheme::MacCormack;
  // Both traces are shared by all fields: back (where the value comes from) and, for
  // MacCormack, ahead (where the backward step samples the forward result).
  work.cellTrace.resize(maccormack ? 2 * cells : cells);
  const VelocityField field(grid);
  // Decided from the first field's old values once: the fields are swapped as they are done.
  work.kept.assign(keepBeyond > 0.0 ? cells : 0, 0);
  const double* first = fields[0]->data();
  auto kept = [&](size_t c) { return keepBeyond > 0.0 && work.kept[c]; };
  forEachSample(tasks, d, [&](int i, int j, int k, size_t c) {
    if (keepBeyond > 0.0 && std::abs(first[c]) >= keepBeyond) {
      work.kept[c] = 1;
      return;
    }
    const Eigen::Vector3d x = grid.cellCentre(i, j, k);
    const Eigen::Vector3d u = grid.cellVelocity(i, j, k);
    work.cellTrace[c] = latticeCoordinate(s, trace(field, x, u, dt), 3);
    if (maccormack) work.cellTrace[cells + c] = latticeCoordinate(s, trace(field, x, u, -dt), 3);
  });
  work.forward.resize(cells);
  std::vector<double>& out = work.advected[0];
  out.resize(cells);
  const uint8_t* faces = openFaces != nullptr ? openFaces->faces.data() : nullptr;
  const uint8_t* blockOpen = openFaces != nullptr ? openFaces->blockOpen.data() : nullptr;
  auto sample = [&](const double* values, const Eigen::Vector3d& at, SampleRange* range) {
    return faces != nullptr ? connectedTrilinearSample(values, d, at, faces, blockOpen, range)
                            : trilinearSample(values, d, at, range);
  };
  for (int which = 0; which < fieldCount; ++which) {
    std::vector<double>& old = *fields[which];
    // Cells with no open face (inside a solid) are not advected: they hold the solid value.
    auto solid = [&](size_t c) { return faces != nullptr && !(faces[c] & kCellIsFluid); };
    const double solidValue = solidValues != nullptr ? solidValues[which] : 0.0;
    auto solidResult = [&](size_t c) { return solidValues != nullptr ? solidValue : old[c]; };
    if (!maccormack) {
      forEachSample(tasks, d, [&](int, int, int, size_t c) {
        out[c] = solid(c) ? solidResult(c) : kept(c) ? old[c] : sample(old.data(), work.cellTrace[c], nullptr);
      });
      old.swap(out);
      continue;
    }
    work.rangeLo.resize(cells);
    work.rangeHi.resize(cells);
    forEachSample(tasks, d, [&](int, int, int, size_t c) {
      if (solid(c) || kept(c)) {
        work.forward[c] = work.rangeLo[c] = work.rangeHi[c] = solid(c) ? solidResult(c) : old[c];
        return;
      }
      SampleRange range;
      work.forward[c] = sample(old.data(), work.cellTrace[c], &range);
      work.rangeLo[c] = range.lo, work.rangeHi[c] = range.hi;
    });
    forEachSample(tasks, d, [&](int, int, int, size_t c) {
      if (solid(c) || kept(c)) {
        out[c] = work.forward[c];
        return;
      }
      const double backAgain = sample(work.forward.data(), work.cellTrace[cells + c], nullptr);
      out[c] = std::clamp(work.forward[c] + 0.5 * (old[c] - backAgain), work.rangeLo[c], work.rangeHi[c]);
    });
    old.swap(out);
  }
}

}  // namespace vp
