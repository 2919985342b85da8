// Implicit cut-cell pressure operator (see cut_cell_poisson.h).
#include "fluid/pressure/cut_cell_poisson.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "fluid/cell_lattice.h"
#include "fluid/pressure/poisson_rows.h"
#include "fluid/surface/free_surface.h"
#include "gpu_kernels/poisson_build_kernels.h"

namespace vp {
namespace {

constexpr int64_t kCellGrain = 4096;
constexpr int64_t kRowGrain = 16;

}  // namespace

Status checkCutCellPoissonInputs(const MacGrid& grid, const FaceFractionField& fractions) {
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
  // Region labels hold cell indices while they are built (labelFluidRegions).
  if (grid.cellCount() > INT32_MAX)
    return fail(Status::InvalidArgument, "cut-cell poisson: grid (%d, %d, %d) has too many cells for 32-bit labels",
                grid.spec.nx, grid.spec.ny, grid.spec.nz);
  return Status::Ok;
}

Status buildCutCellPoisson(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                           CutCellPoisson* op, const double* liquidPhi) {
  if (op == nullptr) return fail(Status::InvalidArgument, "cut-cell poisson: op is null");
  VP_TRY(checkCutCellPoissonInputs(grid, fractions));
  SlabPasses passes(tasks);
  appendBuildCutCellPoisson(grid, fractions, op, liquidPhi, &passes);
  passes.runAll();
  return Status::Ok;
}

namespace {

// What the build's kernel bodies read (gpu_kernels/poisson_build_kernels.h).
kernels::PoissonBuildFields buildFields(const MacGrid& grid, const FaceFractionField& fractions,
                                        const double* liquidPhi) {
  kernels::PoissonBuildFields in;
  for (int a = 0; a < 3; ++a) in.open[a] = fractions.open[a].data();
  in.liquidPhi = liquidPhi;
  in.grid = grid.layout();
  return in;
}

// Couplings (and, with a free surface, open fractions) of the faces of axis a in face rows
// [begin, end); only interior faces couple, index 1 .. cells-1 along the axis. `changed`
// (optional): the rows owning faces whose values changed are raised (changed_rows.h).
void buildCouplingRows(const kernels::PoissonBuildFields& in, int a, int64_t begin, int64_t end, CutCellPoisson* op,
                       ChangedRows* changed) {
  const int64_t nx = in.grid.nx, ny = in.grid.ny, nz = in.grid.nz;
  const int64_t rowLength = nx + (a == 0), rowsAlongY = ny + (a == 1);
  // Cell index step along a: the face's high cell is (i, j, k), its low cell that less the step.
  const int64_t step = a == 0 ? 1 : a == 1 ? nx : nx * ny;
  double* coupling = op->coupling[a].data();
  double* openFraction = in.liquidPhi != nullptr ? op->openFraction[a].data() : nullptr;
  for (int64_t row = begin; row < end; ++row) {
    const int64_t j = row % rowsAlongY, k = row / rowsAlongY, f0 = rowLength * row;
    // Interior faces along a: i in [i0, i1) of the row (a = 0), or the whole row or none.
    const int64_t along = a == 1 ? j : k;
    const bool interiorRow = a == 0 || (along > 0 && along < in.grid.cells(a));
    const int64_t i0 = !interiorRow ? rowLength : a == 0 ? 1 : 0;
    const int64_t i1 = !interiorRow ? rowLength : a == 0 ? rowLength - 1 : rowLength;
    const int64_t cell0 = nx * (j + ny * k);  // the high cell of face i is cell0 + i
    bool rowChanged = false;
    for (int64_t i = 0; i < rowLength; ++i) {
      kernels::FaceCoupling face{0.0, 0.0};
      if (i >= i0 && i < i1) face = kernels::interiorFaceCoupling(in, a, f0 + i, cell0 + i - step, cell0 + i);
      if (changed != nullptr) rowChanged = rowChanged || !sameBits(coupling[f0 + i], face.coupling);
      coupling[f0 + i] = face.coupling;
      if (openFraction == nullptr) continue;
      if (changed != nullptr) rowChanged = rowChanged || !sameBits(openFraction[f0 + i], face.open);
      openFraction[f0 + i] = face.open;
    }
    if (rowChanged) changed->raise(owningRow(a, row, ny, nz));
  }
}

// Diagonal (and, with a free surface, air flags, level set and surface terms) of the cells of
// grid rows [begin, end); `changed` (optional) as for buildCouplingRows.
void buildDiagonalRows(const kernels::PoissonBuildFields& in, int64_t begin, int64_t end, CutCellPoisson* op,
                       ChangedRows* changed) {
  const int64_t nx = in.grid.nx, ny = in.grid.ny, nz = in.grid.nz;
  for (int64_t row = begin; row < end; ++row) {
    const int64_t j = row % ny, k = row / ny, c0 = nx * row;
    const bool interiorRow = j > 0 && j + 1 < ny && k > 0 && k + 1 < nz;
    for (int64_t i = 0; i < nx; ++i) {
      const kernels::CellDiagonal d = interiorRow && i > 0 && i + 1 < nx ? kernels::interiorCellDiagonalAt(in, i, j, k)
                                                                          : kernels::cellDiagonalAt(in, i, j, k);
      const size_t c = static_cast<size_t>(c0 + i);
      storeTracked(&op->diagonal[c], d.diagonal, changed, row);
      if (in.liquidPhi == nullptr) continue;
      op->air[c] = d.air ? 1 : 0;
      op->liquidPhi[c] = in.liquidPhi[c];
      storeTracked(&op->surfaceDirichlet[c], d.surface, changed, row);
    }
  }
}

template <class T>
void sizeOrClear(Array<T>& values, bool used, size_t count) {
  if (used) values.resize(count);
  else values.clear();
}

}  // namespace

void sizeCutCellPoisson(const MacGridSpec& grid, bool freeSurface, bool air, CutCellPoisson* op) {
  const size_t nx = static_cast<size_t>(grid.nx), ny = static_cast<size_t>(grid.ny), nz = static_cast<size_t>(grid.nz);
  const size_t faces[3] = {(nx + 1) * ny * nz, nx * (ny + 1) * nz, nx * ny * (nz + 1)};
  op->grid = grid;
  for (int a = 0; a < 3; ++a) {
    op->coupling[a].resize(faces[a]);
    sizeOrClear(op->openFraction[a], freeSurface, faces[a]);
  }
  op->diagonal.resize(nx * ny * nz);
  sizeOrClear(op->air, air, nx * ny * nz);
  sizeOrClear(op->liquidPhi, freeSurface, nx * ny * nz);
  sizeOrClear(op->surfaceDirichlet, freeSurface, nx * ny * nz);
}

void appendBuildCutCellPoisson(const MacGrid& grid, const FaceFractionField& fractions, CutCellPoisson* op,
                               const double* liquidPhi, SlabPasses* passes, ChangedRows* changed) {
  const MacGrid* g = &grid;
  const FaceFractionField* f = &fractions;
  passes->addStep([g, f, op, liquidPhi, passes, changed] {
    const bool sameShape = sameGrid(op->grid, g->spec) && op->diagonal.size() == static_cast<size_t>(g->cellCount()) &&
                           op->liquidPhi.empty() == (liquidPhi == nullptr);
    sizeCutCellPoisson(g->spec, liquidPhi != nullptr, liquidPhi != nullptr, op);
    if (changed != nullptr) {
      changed->sizeFor(static_cast<int64_t>(g->spec.ny) * g->spec.nz);
      if (!sameShape) changed->raiseAll();
    }
    const kernels::PoissonBuildFields in = buildFields(*g, *f, liquidPhi);
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3i d = g->faceDims(a);
      passes->addParallel(static_cast<int64_t>(d.z()) * d.y(), d.x(), kRowGrain,
                          [in, op, a, changed](int64_t b, int64_t e) { buildCouplingRows(in, a, b, e, op, changed); });
    }
    passes->addParallel(static_cast<int64_t>(g->spec.ny) * g->spec.nz, g->spec.nx, kRowGrain,
                        [in, op, changed](int64_t b, int64_t e) { buildDiagonalRows(in, b, e, op, changed); });
    appendLabelFluidRegions(op, passes);
    appendComputeRowSpans(op, passes);
  });
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

namespace {

// The diagonal less the couplings of the cell's faces in the order -x, +x, -y, +y, -z, +z, where
// that is more than round-off of a fluid cell's diagonal.
inline double dirichletRemainder(double diag, const double couplings[6]) {
  const double rest = diag - couplings[0] - couplings[1] - couplings[2] - couplings[3] - couplings[4] - couplings[5];
  return ((diag > 0.0) & (rest > 1e-12 * diag)) ? rest : 0.0;
}

}  // namespace

double dirichletPart(const CutCellPoisson& op, int64_t cell) {
  double couplings[6];
  int f = 0;
  forEachCellFace(op.grid, cell,
                  [&](int a, int64_t face, int64_t) { couplings[f++] = op.coupling[a][static_cast<size_t>(face)]; });
  return dirichletRemainder(op.diagonal[static_cast<size_t>(cell)], couplings);
}

void dirichletPartsOfRow(const CutCellPoisson& op, int64_t row, double* parts) {
  const poisson_rows::Stencil<double> s(op);
  const poisson_rows::Row<double> r(s, row % s.ny, row / s.ny, nullptr);
  for (int64_t i = 0; i < s.nx; ++i) {
    const double couplings[6] = {r.cu[i], r.cu[i + 1], r.cvLow[i], r.cvHigh[i], r.cwLow[i], r.cwHigh[i]};
    parts[i] = dirichletRemainder(r.diagonal[i], couplings);
  }
}

namespace {

void startFluidRegions(CutCellPoisson* op) {
  op->region.resize(op->diagonal.size());
  op->regionFloating.clear();
  op->regionCellCount.clear();
  op->fluidCellCount = 0;
}

int32_t findRoot(int32_t* parent, int32_t c) {
  while (parent[c] != c) {
    parent[c] = parent[parent[c]];  // path halving: links only ever point to smaller indices
    c = parent[c];
  }
  return c;
}

// First scan, cells [begin, end) in order: region[c] becomes a smaller cell of c's region so
// far (c itself for a root), -1 off fluid. Linking the larger root under the smaller keeps
// every link pointing down, so each region's root ends as its first cell.
void linkFluidRegions(CutCellPoisson* op, int64_t begin, int64_t end) {
  int32_t* parent = op->region.data();
  const double* diagonal = op->diagonal.data();
  const double *cu = op->coupling[0].data(), *cv = op->coupling[1].data(), *cw = op->coupling[2].data();
  const int64_t nx = op->grid.nx, ny = op->grid.ny, sz = nx * ny;
  auto link = [&](int64_t c, int64_t nb, double coupling) {
    if (parent[nb] < 0 || !(coupling > 0.0)) return;
    const int32_t r = findRoot(parent, static_cast<int32_t>(nb)), s = findRoot(parent, static_cast<int32_t>(c));
    if (r != s) parent[std::max(r, s)] = std::min(r, s);
  };
  int64_t i = begin % nx, j = (begin / nx) % ny, k = begin / sz;
  for (int64_t c = begin; c < end; ++c) {
    if (diagonal[c] > 0.0) {
      parent[c] = static_cast<int32_t>(c);
      // Only the faces toward smaller cells (-x, -y, -z): the others link when their cell comes.
      // Face indices (cut_cell_poisson.h): -x face i + (nx + 1)(j + ny k) = c + j + ny k, -y
      // face i + nx (j + (ny + 1) k) = c + nx k, -z face c.
      if (i > 0) link(c, c - 1, cu[c + j + ny * k]);
      if (j > 0) link(c, c - nx, cv[c + nx * k]);
      if (k > 0) link(c, c - sz, cw[c]);
    } else {
      parent[c] = -1;
    }
    if (++i == nx) {
      i = 0;
      if (++j == ny) j = 0, ++k;
    }
  }
}

// Second scan, in order: a root opens the next region; any other cell takes the region of its
// link, a smaller cell already numbered.
void numberFluidRegions(CutCellPoisson* op, int64_t begin, int64_t end) {
  int32_t* region = op->region.data();
  for (int64_t c = begin; c < end; ++c) {
    const int32_t link = region[c];
    if (link < 0) continue;
    int32_t id;
    if (link == c) {
      id = static_cast<int32_t>(op->regionFloating.size());
      op->regionFloating.push_back(1);
      op->regionCellCount.push_back(0);
    } else {
      id = region[link];
    }
    region[c] = id;
    // A region stops floating at its first cell with a Dirichlet part; later ones need no test.
    uint8_t& floating = op->regionFloating[static_cast<size_t>(id)];
    if (floating && dirichletPart(*op, c) > 0.0) floating = 0;
    ++op->regionCellCount[static_cast<size_t>(id)];
    ++op->fluidCellCount;
  }
}

void computeRowSpansOfRows(CutCellPoisson* op, int64_t begin, int64_t end) {
  const poisson_rows::Stencil<double> s(*op);
  int32_t* span = op->rowSpan.data();
  for (int64_t row = begin; row < end; ++row) {
    const double* d = s.diagonal + s.nx * row;
    int64_t first = 0, last = s.nx;
    while (first < s.nx && !(d[first] > 0.0)) ++first;
    while (last > first && !(d[last - 1] > 0.0)) --last;
    span[2 * row] = static_cast<int32_t>(first);
    span[2 * row + 1] = static_cast<int32_t>(last);
  }
}

}  // namespace

void labelFluidRegions(CutCellPoisson* op) {
  const int64_t cells = static_cast<int64_t>(op->diagonal.size());
  startFluidRegions(op);
  linkFluidRegions(op, 0, cells);
  numberFluidRegions(op, 0, cells);
}

void appendLabelFluidRegions(CutCellPoisson* op, SlabPasses* passes) {
  passes->addStep([op, passes] {
    startFluidRegions(op);
    const int64_t cells = static_cast<int64_t>(op->diagonal.size());
    passes->addSerial(cells, 1, [op](int64_t begin, int64_t end) { linkFluidRegions(op, begin, end); });
    passes->addSerial(cells, 1, [op](int64_t begin, int64_t end) { numberFluidRegions(op, begin, end); });
  });
}

void computeRowSpans(TaskSystem& tasks, CutCellPoisson* op) {
  SlabPasses passes(tasks);
  appendComputeRowSpans(op, &passes);
  passes.runAll();
}

void appendComputeRowSpans(CutCellPoisson* op, SlabPasses* passes) {
  passes->addStep([op, passes] {
    const poisson_rows::Stencil<double> s(*op);
    op->rowSpan.resize(static_cast<size_t>(2 * s.rows()));
    passes->addParallel(s.rows(), s.nx, s.rowGrain(),
                        [op](int64_t begin, int64_t end) { computeRowSpansOfRows(op, begin, end); });
  });
}

void applyCutCellPoisson(TaskSystem& tasks, const CutCellPoisson& op, const double* p, double* out) {
  const poisson_rows::Stencil<double> s(op);
  poisson_rows::forEachRow(tasks, s, [&](int64_t j, int64_t k, int64_t) { poisson_rows::applyRow(s, j, k, p, out); });
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
  Array<double> mean(regions, 0.0);
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
  parallelFor(tasks, grid.cellCount(), kCellGrain, [&](int64_t begin, int64_t end) {
    computeNetOutflowCells(grid, fractions, op, begin, end, outflow);
  });
}

kernels::NetOutflowFields netOutflowFields(const MacGrid& grid, const FaceFractionField& fractions) {
  kernels::NetOutflowFields in;
  for (int a = 0; a < 3; ++a) {
    in.open[a] = fractions.open[a].data();
    in.solidVelocity[a] = fractions.solidVelocity[a].data();
    in.velocity[a] = grid.velocity[a].data();
  }
  in.grid = grid.layout();
  return in;
}

void computeNetOutflowCells(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                            int64_t begin, int64_t end, double* outflow) {
  const kernels::NetOutflowFields in = netOutflowFields(grid, fractions);
  forCellsInRange(grid.spec, begin, end, [&](int64_t c, int i, int j, int k) {
    outflow[c] = op.region[static_cast<size_t>(c)] < 0 ? 0.0 : kernels::netOutflowCell(in, i, j, k);
  });
}

}  // namespace vp
