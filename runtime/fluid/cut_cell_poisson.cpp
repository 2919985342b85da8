// Implicit cut-cell pressure operator (see cut_cell_poisson.h).
#include "fluid/cut_cell_poisson.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "fluid/free_surface.h"
#include "fluid/poisson_rows.h"

namespace vp {
namespace {

constexpr int64_t kCellGrain = 4096;

// Calls visit(axis, highSide, i, j, k of the face, i, j, k of the neighbour cell) for the six faces.
template <class Visit>
void forEachFace(int i, int j, int k, const Visit& visit) {
  visit(0, false, i, j, k, i - 1, j, k);
  visit(0, true, i + 1, j, k, i + 1, j, k);
  visit(1, false, i, j, k, i, j - 1, k);
  visit(1, true, i, j + 1, k, i, j + 1, k);
  visit(2, false, i, j, k, i, j, k - 1);
  visit(2, true, i, j, k + 1, i, j, k + 1);
}

bool inside(const MacGridSpec& g, int i, int j, int k) {
  return i >= 0 && j >= 0 && k >= 0 && i < g.nx && j < g.ny && k < g.nz;
}

}  // namespace

double effectiveOpenFraction(const MacGrid& grid, const FaceFractionField& fractions, int axis, int i,
                             int j, int k) {
  if (grid.isWallFace(axis, i, j, k)) return 0.0;
  const double open = fractions.open[axis][grid.faceIndex(axis, i, j, k)];
  return open < kMinOpenFraction ? 0.0 : open;
}

Status buildCutCellPoisson(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                           CutCellPoisson* op, const double* liquidPhi) {
  if (op == nullptr) return fail(Status::InvalidArgument, "cut-cell poisson: op is null");
  if (!sameGrid(grid.spec, fractions.grid))
    return fail(Status::InvalidArgument,
                "cut-cell poisson: face fractions grid (%d, %d, %d, h %g) differs from the MAC grid "
                "(%d, %d, %d, h %g)", fractions.grid.nx, fractions.grid.ny, fractions.grid.nz,
                fractions.grid.h, grid.spec.nx, grid.spec.ny, grid.spec.nz, grid.spec.h);
  for (int a = 0; a < 3; ++a) {
    if (fractions.open[a].size() != grid.velocity[a].size() ||
        fractions.solidVelocity[a].size() != grid.velocity[a].size())
      return fail(Status::InvalidArgument, "cut-cell poisson: face arrays of axis %d have %zu entries, "
                  "expected %zu", a, fractions.open[a].size(), grid.velocity[a].size());
  }
  const MacGridSpec& g = grid.spec;
  op->grid = g;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid.faceDims(a);
    std::vector<double>& c = op->coupling[a];
    c.assign(grid.velocity[a].size(), 0.0);
    if (liquidPhi != nullptr) op->openFraction[a].assign(grid.velocity[a].size(), 0.0);
    else op->openFraction[a].clear();
    // Interior faces only: index 1 .. cells-1 along the axis.
    parallelFor(tasks, static_cast<int64_t>(d.z()) * d.y(), 16, [&](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) {
        const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
        for (int i = 0; i < d.x(); ++i) {
          const int along = a == 0 ? i : a == 1 ? j : k;
          if (along == 0 || along == d[a] - 1) continue;
          const size_t face = grid.faceIndex(a, i, j, k);
          const double open = effectiveOpenFraction(grid, fractions, a, i, j, k);
          if (liquidPhi != nullptr) {
            op->openFraction[a][face] = open;
            // Only liquid-liquid faces couple; a liquid-air face is a diagonal term below.
            Eigen::Vector3i low(i, j, k);
            low[a] -= 1;
            if (!isLiquid(liquidPhi[grid.cellIndex(i, j, k)]) ||
                !isLiquid(liquidPhi[grid.cellIndex(low.x(), low.y(), low.z())]))
              continue;
          }
          c[face] = open;
        }
      }
    });
  }
  const int64_t cells = grid.cellCount();
  op->diagonal.assign(static_cast<size_t>(cells), 0.0);
  if (liquidPhi != nullptr) {
    op->air.assign(static_cast<size_t>(cells), 0);
    op->liquidPhi.assign(liquidPhi, liquidPhi + cells);
    op->surfaceDirichlet.assign(static_cast<size_t>(cells), 0.0);
  } else {
    op->air.clear();
    op->liquidPhi.clear();
    op->surfaceDirichlet.clear();
  }
  parallelFor(tasks, cells, kCellGrain, [&](int64_t begin, int64_t end) {
    for (int64_t c = begin; c < end; ++c) {
      const int i = static_cast<int>(c % g.nx), j = static_cast<int>((c / g.nx) % g.ny),
                k = static_cast<int>(c / (static_cast<int64_t>(g.nx) * g.ny));
      if (liquidPhi != nullptr && !isLiquid(liquidPhi[c])) {
        op->diagonal[static_cast<size_t>(c)] = 0.0;  // air: p = 0, no row
        bool open = false;
        forEachFace(i, j, k, [&](int a, bool, int fi, int fj, int fk, int, int, int) {
          open = open || effectiveOpenFraction(grid, fractions, a, fi, fj, fk) > 0.0;
        });
        op->air[static_cast<size_t>(c)] = open ? 1 : 0;
        continue;
      }
      double sum = 0.0, surface = 0.0;
      forEachFace(i, j, k, [&](int a, bool, int fi, int fj, int fk, int ni, int nj, int nk) {
        const double open = effectiveOpenFraction(grid, fractions, a, fi, fj, fk);
        if (liquidPhi != nullptr && open > 0.0 && inside(g, ni, nj, nk)) {
          const double phiNb = liquidPhi[grid.cellIndex(ni, nj, nk)];
          if (!isLiquid(phiNb)) {
            const double term = open / freeSurfaceTheta(liquidPhi[c], phiNb);
            sum += term;  // summed in face order as ever, so the fine operator is bitwise unchanged
            surface += term;
            return;
          }
        }
        sum += open;
      });
      op->diagonal[static_cast<size_t>(c)] = sum;
      if (liquidPhi != nullptr) op->surfaceDirichlet[static_cast<size_t>(c)] = surface;
    }
  });

  labelFluidRegions(op);
  computeRowSpans(tasks, op);
  return Status::Ok;
}

namespace {

// Calls visit(axis, face index, neighbour cell index or -1 outside the grid) for the six faces
// of cell c.
template <class Visit>
void forEachCellFace(const MacGridSpec& g, int64_t c, const Visit& visit) {
  const int64_t nx = g.nx, ny = g.ny, nz = g.nz, sz = nx * ny;
  const int64_t i = c % nx, j = (c / nx) % ny, k = c / sz;
  const int64_t fu = i + (nx + 1) * (j + ny * k), fv = i + nx * (j + (ny + 1) * k);
  visit(0, fu, i > 0 ? c - 1 : -1);
  visit(0, fu + 1, i + 1 < nx ? c + 1 : -1);
  visit(1, fv, j > 0 ? c - nx : -1);
  visit(1, fv + nx, j + 1 < ny ? c + nx : -1);
  visit(2, c, k > 0 ? c - sz : -1);
  visit(2, c + sz, k + 1 < nz ? c + sz : -1);
}

}  // namespace

double dirichletPart(const CutCellPoisson& op, int64_t cell) {
  const double diag = op.diagonal[static_cast<size_t>(cell)];
  if (!(diag > 0.0)) return 0.0;
  double rest = diag;
  forEachCellFace(op.grid, cell, [&](int a, int64_t face, int64_t) { rest -= op.coupling[a][static_cast<size_t>(face)]; });
  return rest > 1e-12 * diag ? rest : 0.0;
}

void labelFluidRegions(CutCellPoisson* op) {
  const int64_t cells = static_cast<int64_t>(op->diagonal.size());
  op->region.assign(static_cast<size_t>(cells), -1);
  op->regionFloating.clear();
  op->regionCellCount.clear();
  op->fluidCellCount = 0;
  std::vector<int64_t> queue;
  for (int64_t seed = 0; seed < cells; ++seed) {
    if (op->region[static_cast<size_t>(seed)] >= 0 || !(op->diagonal[static_cast<size_t>(seed)] > 0.0)) continue;
    const int32_t id = static_cast<int32_t>(op->regionFloating.size());
    bool floating = true;
    queue.clear();
    queue.push_back(seed);
    op->region[static_cast<size_t>(seed)] = id;
    for (size_t head = 0; head < queue.size(); ++head) {
      const int64_t c = queue[head];
      if (dirichletPart(*op, c) > 0.0) floating = false;
      forEachCellFace(op->grid, c, [&](int a, int64_t face, int64_t nb) {
        if (nb < 0 || !(op->coupling[a][static_cast<size_t>(face)] > 0.0)) return;
        if (op->region[static_cast<size_t>(nb)] < 0) {
          op->region[static_cast<size_t>(nb)] = id;
          queue.push_back(nb);
        }
      });
    }
    op->regionFloating.push_back(floating ? 1 : 0);
    op->regionCellCount.push_back(static_cast<int64_t>(queue.size()));
    op->fluidCellCount += static_cast<int64_t>(queue.size());
  }
}

void computeRowSpans(TaskSystem& tasks, CutCellPoisson* op) {
  const poisson_rows::Stencil<double> s(*op);
  op->rowSpan.assign(static_cast<size_t>(2 * s.rows()), 0);
  int32_t* span = op->rowSpan.data();
  parallelFor(tasks, s.rows(), s.rowGrain(), [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const double* d = s.diagonal + s.nx * row;
      int64_t first = 0, last = s.nx;
      while (first < s.nx && !(d[first] > 0.0)) ++first;
      while (last > first && !(d[last - 1] > 0.0)) --last;
      span[2 * row] = static_cast<int32_t>(first);
      span[2 * row + 1] = static_cast<int32_t>(last);
    }
  });
}

void applyCutCellPoisson(TaskSystem& tasks, const CutCellPoisson& op, const double* p, double* out) {
  const poisson_rows::Stencil<double> s(op);
  poisson_rows::forEachRow(tasks, s, [&](int64_t j, int64_t k, int64_t c0) {
    const int64_t row = j + s.ny * k;
    double* o = out + c0;
    poisson_rows::clearOutsideSpan(s, row, o);
    const poisson_rows::Row<double> r(s, j, k, p);
    for (int64_t i = s.spanBegin(row), e = s.spanEnd(row); i < e; ++i) {
      const double d = r.diagonal[i];
      o[i] = d > 0.0 ? d * r.x[i] - r.neighbourSum(i) : 0.0;
    }
  });
}

template <class T>
void filterCutCellPoisson(TaskSystem& tasks, const CutCellPoisson& op, T* values) {
  const size_t cells = op.region.size();
  const size_t regions = op.regionFloating.size();
  bool anyFloating = false;
  for (uint8_t f : op.regionFloating) anyFloating = anyFloating || f != 0;
  if (!anyFloating) {
    parallelFor(tasks, static_cast<int64_t>(cells), kCellGrain, [&](int64_t begin, int64_t end) {
      for (int64_t c = begin; c < end; ++c)
        if (op.region[static_cast<size_t>(c)] < 0) values[c] = T(0);
    });
    return;
  }
  std::vector<double> mean(regions, 0.0);
  for (size_t c = 0; c < cells; ++c) {
    const int32_t r = op.region[c];
    if (r < 0) values[c] = 0.0;
    else if (op.regionFloating[r]) mean[r] += values[c];
  }
  for (size_t r = 0; r < regions; ++r) mean[r] /= static_cast<double>(op.regionCellCount[r]);
  for (size_t c = 0; c < cells; ++c) {
    const int32_t r = op.region[c];
    if (r >= 0 && op.regionFloating[r]) values[c] = static_cast<T>(values[c] - mean[r]);
  }
}

template void filterCutCellPoisson<double>(TaskSystem&, const CutCellPoisson&, double*);
template void filterCutCellPoisson<float>(TaskSystem&, const CutCellPoisson&, float*);

void computeNetOutflow(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                       const CutCellPoisson& op, double* outflow) {
  const MacGridSpec& g = grid.spec;
  parallelFor(tasks, grid.cellCount(), kCellGrain, [&](int64_t begin, int64_t end) {
    for (int64_t c = begin; c < end; ++c) {
      if (op.region[static_cast<size_t>(c)] < 0) {
        outflow[c] = 0.0;
        continue;
      }
      const int i = static_cast<int>(c % g.nx), j = static_cast<int>((c / g.nx) % g.ny),
                k = static_cast<int>(c / (static_cast<int64_t>(g.nx) * g.ny));
      double sum = 0.0;
      forEachFace(i, j, k, [&](int a, bool high, int fi, int fj, int fk, int, int, int) {
        const size_t f = grid.faceIndex(a, fi, fj, fk);
        const bool wall = grid.isWallFace(a, fi, fj, fk);
        const double open =
            wall ? std::clamp(fractions.open[a][f], 0.0, 1.0) : effectiveOpenFraction(grid, fractions, a, fi, fj, fk);
        const double fluidVelocity = wall ? 0.0 : grid.velocity[a][f];
        const double flux = open * fluidVelocity + (1.0 - open) * fractions.solidVelocity[a][f];
        sum += high ? flux : -flux;
      });
      outflow[c] = sum;
    }
  });
}

}  // namespace vp
