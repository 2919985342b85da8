// Cut-cell and voxel coarsening of the pressure operator (see multigrid_coarsening.h).
#include "fluid/pressure/multigrid_coarsening.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/isa_clones.h"
#include "core/parallel_for.h"
#include "fluid/surface/free_surface.h"
#include "gpu_kernels/coarsening_kernels.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 16;
// Samples of a coarse cell whose pass reads its children.
constexpr int64_t kChildren = 8;
// Fully open fine face, coarsened: 4 fine couplings of 1, halved.
constexpr double kVoxelCoupling = 2.0;

struct Dims {
  int64_t nx, ny, nz;
  explicit Dims(const MacGridSpec& g) : nx(g.nx), ny(g.ny), nz(g.nz) {}
  int64_t cells() const { return nx * ny * nz; }
  int64_t cell(int64_t i, int64_t j, int64_t k) const { return i + nx * (j + ny * k); }
  // Face index on axis a of the face at the low side of cell (i, j, k).
  int64_t face(int a, int64_t i, int64_t j, int64_t k) const {
    return a == 0 ? i + (nx + 1) * (j + ny * k) : a == 1 ? i + nx * (j + (ny + 1) * k) : i + nx * (j + ny * k);
  }
  int64_t along(int a) const { return a == 0 ? nx : a == 1 ? ny : nz; }
  kernels::MacLayout kernelDims() const { return kernels::MacLayout{nx, ny, nz, {}}; }
};

// Diagonal = couplings of the six faces + Dirichlet part, cells of rows [begin, end) for which
// `todo` is set (every row when null); couplings must be set. `changed` (optional): rows whose
// diagonal changed are raised.
void assembleDiagonalRows(const Array<double>& dirichlet, CutCellPoisson* op, int64_t begin, int64_t end,
                          const uint8_t* todo = nullptr, ChangedRows* changed = nullptr) {
  const Dims d(op->grid);
  const double* const coupling[3] = {op->coupling[0].data(), op->coupling[1].data(), op->coupling[2].data()};
  for (int64_t row = begin; row < end; ++row) {
    if (todo != nullptr && !todo[row]) continue;
    const int64_t j = row % d.ny, k = row / d.ny;
    for (int64_t i = 0; i < d.nx; ++i) {
      const int64_t c = d.cell(i, j, k);
      const double diagonal =
          kernels::coarseDiagonalAt(d.kernelDims(), coupling, dirichlet[static_cast<size_t>(c)], i, j, k);
      storeTracked(&op->diagonal[static_cast<size_t>(c)], diagonal, changed, row);
    }
  }
}

// Calls visit(child cell index) for the children of coarse cell (I, J, K) that exist.
template <class Visit>
void forEachChild(const Dims& fine, int64_t I, int64_t J, int64_t K, const Visit& visit) {
  for (int64_t k = 2 * K; k < 2 * K + 2 && k < fine.nz; ++k)
    for (int64_t j = 2 * J; j < 2 * J + 2 && j < fine.ny; ++j)
      for (int64_t i = 2 * I; i < 2 * I + 2 && i < fine.nx; ++i) visit(fine.cell(i, j, k));
}

// Adds a parallel pass over the rows of grid d calling visit(I, J, K) for each cell; a cell
// counts `samplesPerCell` samples (kChildren when it reads its children).
template <class Visit>
void addCellPass(SlabPasses* passes, const Dims& d, int64_t samplesPerCell, Visit visit) {
  passes->addParallel(d.ny * d.nz, d.nx * samplesPerCell, kRowGrain, [d, visit](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row)
      for (int64_t I = 0; I < d.nx; ++I) visit(I, row % d.ny, row / d.ny);
  });
}

// Coarse face values on axis a, interior coarse faces only (boundary couplings stay 0 on every
// level): the fine faces under coarse face index I along its axis sit at fine index 2I <=
// n_fine - 1, always interior. Each of the (up to) 4 fine columns under the coarse face
// conducts from the centre of one coarse cell to the centre of the other through the shared
// fine face `in` and half of each fine face inside the two coarse cells (`inner`, 2I - 1 and
// 2I + 1), in series: 2 / (0.5 / A_{2I-1} + 1 / A_{2I} + 0.5 / A_{2I+1}). That is exactly the
// conductance between the means of the two coarse cells' children along a chain of four fine
// cells (the coarse unknown being such a mean), and A for three equal fractions A. The coarse
// value is the halved sum of the columns. Taking the shared face alone (the average of the 4
// fine fractions) lets a thin solid that crosses a coarse cell without covering the shared
// faces (the slanted plate, 1-3 fine cells thick) leak on the coarse levels, which then couple
// both of its sides: iterations to 1e-6 on the plate tank at 64/128/192^3 fell from 11/12/13 to
// 8/8/11 with the series rule (liquid tank 10/11/11 -> 7/7/11).
// Coarse faces per chunk of a row in addColumnConductances (its terms live on the stack).
constexpr int64_t kFaceChunk = 128;

// Adds one fine column's conductance to sum[I] for the coarse faces I in [I0, I1) of a row:
// coarse face I's shared fine face is in[first + 2 I], the faces behind it inner[... - along]
// and, when behindHigh, inner[... + along] (otherwise the coarse cell on the high side has one
// child along the axis, so the column ends at the shared face). A column with a closed face
// adds nothing. The terms are computed for every face and then added where the column is
// open, so both loops vectorize; a sum gains the same terms in the same order as face by face.
VP_ISA_CLONES
void addColumnConductances(const double* in, const double* inner, int64_t first, int64_t along, bool behindHigh,
                           int64_t I0, int64_t I1, double* sum) {
  double term[kFaceChunk];
  for (int64_t c0 = I0; c0 < I1; c0 += kFaceChunk) {
    const int64_t n = std::min(kFaceChunk, I1 - c0);
    const double* shared = in + first + 2 * c0;
    const double* low = inner + first + 2 * c0 - along;
    double* out = sum + c0;
    if (behindHigh) {
      const double* high = low + 2 * along;
      for (int64_t m = 0; m < n; ++m)
        term[m] = kernels::seriesConductance(low[2 * m], shared[2 * m], high[2 * m]);
      for (int64_t m = 0; m < n; ++m)
        out[m] += ((shared[2 * m] > 0.0) & (low[2 * m] > 0.0) & (high[2 * m] > 0.0)) ? term[m] : 0.0;
    } else {
      for (int64_t m = 0; m < n; ++m) term[m] = kernels::endConductance(low[2 * m], shared[2 * m]);
      for (int64_t m = 0; m < n; ++m) out[m] += ((shared[2 * m] > 0.0) & (low[2 * m] > 0.0)) ? term[m] : 0.0;
    }
  }
}

// One row of coarse faces of axis a (the lattice row of faces I = 0 .. count - 1 at (C1, C2),
// output out[I]): the fine columns in the order e2 outer, b2 inner of the axes after a.
void coarseFaceRow(const Dims& f, const Dims& c, int a, int64_t C1, int64_t C2, int64_t count, const double* in,
                   const double* inner, double* out) {
  for (int64_t I = 0; I < count; ++I) out[I] = 0.0;
  const int64_t nxFaces = f.nx + (a == 0);
  if (a == 0) {
    // Interior faces 1 .. c.nx - 1; the last has no face behind on its high side when the fine
    // count is odd.
    const int64_t last = c.nx - 1;
    const bool lastBehindHigh = 2 * last + 1 < f.nx;
    for (int64_t z = 2 * C2; z < 2 * C2 + 2 && z < f.nz; ++z)
      for (int64_t y = 2 * C1; y < 2 * C1 + 2 && y < f.ny; ++y) {
        const int64_t first = nxFaces * (y + f.ny * z);
        addColumnConductances(in, inner, first, 1, true, 1, lastBehindHigh ? last + 1 : last, out);
        if (!lastBehindHigh && last >= 1) addColumnConductances(in, inner, first, 1, false, last, last + 1, out);
      }
  } else {
    const int64_t along = a == 1 ? f.nx : f.nx * f.ny;
    const int64_t C = a == 1 ? C1 : C2;  // the coarse face's index along a
    if (C == 0 || C == c.along(a)) return;
    const bool behindHigh = 2 * C + 1 < f.along(a);
    // a = 1: columns over x (outer) then z; a = 2: over y (outer) then x.
    for (int outer = 0; outer < 2; ++outer)
      for (int inner2 = 0; inner2 < 2; ++inner2) {
        const int64_t dx = a == 1 ? outer : inner2;
        const int64_t other = (a == 1 ? 2 * C2 : 2 * C1) + (a == 1 ? inner2 : outer);  // z (a = 1) or y (a = 2)
        if (other >= (a == 1 ? f.nz : f.ny)) continue;
        const int64_t first = a == 1 ? dx + f.nx * (2 * C + (f.ny + 1) * other) : dx + f.nx * (other + f.ny * 2 * C);
        // Coarse faces whose fine column 2 I + dx exists.
        addColumnConductances(in, inner, first, along, behindHigh, 0, std::min(count, (f.nx - dx + 1) / 2), out);
      }
  }
  for (int64_t I = 0; I < count; ++I) out[I] *= 0.5;
}

// The coarse faces of axis a, a pass over the rows of the coarse face lattice (it writes every
// face, 0 on the domain's). With `todo` (per coarse cell row) only the face rows whose owning
// cell rows are set there (changed_rows.h), and `changed` raises the owners of rows that changed.
void addCoarseFacePass(SlabPasses* passes, const Dims& f, const Dims& c, int a, const Array<double>* in,
                       const Array<double>* inner, Array<double>* out, const uint8_t* todo, ChangedRows* changed) {
  const int64_t faces[3] = {c.nx + (a == 0), c.ny + (a == 1), c.nz + (a == 2)};
  passes->addParallel(faces[1] * faces[2], faces[0] * kChildren, kRowGrain, [=](int64_t begin, int64_t end) {
    Array<double> row(changed != nullptr ? static_cast<size_t>(faces[0]) : 0);
    for (int64_t r = begin; r < end; ++r) {
      const int64_t C1 = r % faces[1], C2 = r / faces[1];
      double* values = out->data() + faces[0] * r;
      if (todo == nullptr) {
        coarseFaceRow(f, c, a, C1, C2, faces[0], in->data(), inner->data(), values);
        continue;
      }
      const int64_t owner = owningRow(a, r, c.ny, c.nz);
      if (!todo[owner]) continue;
      coarseFaceRow(f, c, a, C1, C2, faces[0], in->data(), inner->data(), row.data());
      bool same = true;
      for (int64_t I = 0; I < faces[0]; ++I) same = same && sameBits(values[I], row[static_cast<size_t>(I)]);
      if (same) continue;
      std::copy(row.begin(), row.end(), values);
      changed->raise(owner);
    }
  });
}

// The free surface of a coarse level, by the fine level's ghost-fluid rule at the coarse spacing.
// The level set is restricted by averaging the children (exact at the coarse centre for a
// linear phi). A coarse cell with a fluid child is fluid (as without a surface, so the
// transfers are unchanged); on each open face towards a coarse cell without fluid children it
// gets A_F / theta, theta = phi_C / (phi_C - phi_N), the ghost value p = 0 sitting on the
// surface. A fluid coarse cell whose centre lies in the air has p close to 0 in the linear
// extrapolation the prolongation makes, so it gets the smallest theta. Summing the children's
// terms instead (the rule of the other Dirichlet parts) keeps the fine theta in units of each
// coarse spacing, so the coarse surface lies too high by a depth that grows with the level, and
// the cycle needs more iterations (figures in docs/choices.md, Pressure solve).
// Where no such face exists (air pockets smaller than the coarse cell), the summed rule stays.
// Both passes run over every coarse cell: the level set moves wherever the liquid does. With
// `todo`, a row whose surface terms changed is raised in `changed` and set in todo.
void addCoarseFreeSurfacePasses(SlabPasses* passes, const CutCellPoisson* fine, const Dims& f, const Dims& c,
                                CutCellPoisson* coarse, Array<uint8_t>* fluidCells, uint8_t* todo,
                                ChangedRows* changed) {
  addCellPass(passes, c, kChildren, [=](int64_t I, int64_t J, int64_t K) {
    double phi = 0.0;
    int children = 0;
    bool anyFluid = false;
    forEachChild(f, I, J, K, [&](int64_t child) {
      phi += fine->liquidPhi[static_cast<size_t>(child)];
      ++children;
      anyFluid = anyFluid || fine->diagonal[static_cast<size_t>(child)] > 0.0;
    });
    const size_t cell = static_cast<size_t>(c.cell(I, J, K));
    coarse->liquidPhi[cell] = phi / children;
    (*fluidCells)[cell] = anyFluid ? 1 : 0;
  });
  kernels::CoarseSurfaceFields in;
  in.coarse = c.kernelDims();
  in.fine = f.kernelDims();
  in.liquidPhi = coarse->liquidPhi.data();
  in.fluid = fluidCells->data();
  for (int a = 0; a < 3; ++a) in.openFraction[a] = coarse->openFraction[a].data();
  in.fineSurface = fine->surfaceDirichlet.data();
  addCellPass(passes, c, 1, [=](int64_t I, int64_t J, int64_t K) {
    const size_t cell = static_cast<size_t>(c.cell(I, J, K));
    const double surface = kernels::coarseSurfaceTerm(in, I, J, K);
    if (todo != nullptr && !sameBits(coarse->surfaceDirichlet[cell], surface)) {
      changed->raise(J + c.ny * K);
      todo[J + c.ny * K] = 1;  // the pass's rows are its units: one worker writes this row's flag
    }
    coarse->surfaceDirichlet[cell] = surface;
  });
}

// The Dirichlet parts of coarse rows [begin, end) (those set in `todo`, when given): the halved
// sum of the children's, less their free-surface parts (placed again at this level's spacing by
// the free-surface passes, whose result is added), summed in forEachChild's order.
void coarseDirichletRows(const CutCellPoisson& fine, const Dims& f, const Dims& c, bool freeSurface,
                         const CutCellPoisson& coarse, int64_t begin, int64_t end, const uint8_t* todo,
                         double* dirichlet) {
  Array<double> parts(static_cast<size_t>(4 * f.nx));
  for (int64_t row = begin; row < end; ++row) {
    if (todo != nullptr && !todo[row]) continue;
    const int64_t J = row % c.ny, K = row / c.ny;
    int childRows = 0;
    for (int64_t k = 2 * K; k < 2 * K + 2 && k < f.nz; ++k)
      for (int64_t j = 2 * J; j < 2 * J + 2 && j < f.ny; ++j, ++childRows) {
        const int64_t fineRow = j + f.ny * k;
        double* p = parts.data() + f.nx * childRows;
        dirichletPartsOfRow(fine, fineRow, p);
        if (!freeSurface) continue;
        const double* surface = fine.surfaceDirichlet.data() + f.nx * fineRow;
        for (int64_t i = 0; i < f.nx; ++i) p[i] = std::max(0.0, p[i] - surface[i]);
      }
    for (int64_t I = 0; I < c.nx; ++I) {
      double sum = 0.0;
      for (int r = 0; r < childRows; ++r) {
        const double* p = parts.data() + f.nx * r;
        sum += p[2 * I];
        if (2 * I + 1 < f.nx) sum += p[2 * I + 1];
      }
      const int64_t cell = c.cell(I, J, K);
      dirichlet[cell] = 0.5 * sum + (freeSurface ? coarse.surfaceDirichlet[static_cast<size_t>(cell)] : 0.0);
    }
  }
}

// Per coarse row, whether an update recomputes it: the rows within reach of a raised fine row
// or raised themselves (by an update stopped before it finished). Coarse row (J, K) reads fine
// rows 2J - 1 .. 2J + 3 and 2K - 1 .. 2K + 3 at most: its children's (2J, 2J + 1), the faces
// behind its low coarse faces (2J - 1), and for its diagonal the faces of its high coarse faces
// (up to 2J + 3) and its children's high faces (owned by row 2J + 2, changed_rows.h).
void addRecomputedRowsPass(SlabPasses* passes, const Dims& f, const Dims& c, const ChangedRows* fineChanged,
                           const ChangedRows* coarseChanged, uint8_t* todo) {
  passes->addParallel(c.ny * c.nz, kChildren, kRowGrain, [=](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t J = row % c.ny, K = row / c.ny;
      bool reached = coarseChanged->raised(row);
      for (int64_t k = std::max<int64_t>(0, 2 * K - 1); k <= std::min(f.nz - 1, 2 * K + 3) && !reached; ++k)
        for (int64_t j = std::max<int64_t>(0, 2 * J - 1); j <= std::min(f.ny - 1, 2 * J + 3); ++j)
          reached = reached || fineChanged->raised(j + f.ny * k);
      todo[row] = reached ? 1 : 0;
    }
  });
}

// The last passes of either coarsening: the diagonal from the couplings and scratch->dirichlet
// (the rows set in `todo`, when given, raising those that change in `changed`), then the
// regions and row spans.
void addCoarseDiagonalPasses(SlabPasses* passes, const Dims& c, CutCellPoisson* coarse, CoarseningScratch* scratch,
                             const uint8_t* todo = nullptr, ChangedRows* changed = nullptr) {
  passes->addParallel(c.ny * c.nz, c.nx, kRowGrain, [=](int64_t begin, int64_t end) {
    assembleDiagonalRows(scratch->dirichlet, coarse, begin, end, todo, changed);
  });
  appendLabelFluidRegions(coarse, passes);
  appendComputeRowSpans(coarse, passes);
}

}  // namespace

MacGridSpec coarseGridSpec(const MacGridSpec& fine) {
  MacGridSpec c = fine;
  c.nx = (fine.nx + 1) / 2;
  c.ny = (fine.ny + 1) / 2;
  c.nz = (fine.nz + 1) / 2;
  c.h = 2.0 * fine.h;
  return c;
}

Status coarsenCutCell(TaskSystem& tasks, const CutCellPoisson& fine, CutCellPoisson* coarse) {
  if (coarse == nullptr) return fail(Status::InvalidArgument, "multigrid coarsening: coarse is null");
  SlabPasses passes(tasks);
  CoarseningScratch scratch;
  appendCoarsenCutCell(fine, coarse, &scratch, &passes, nullptr, nullptr);
  passes.runAll();
  return Status::Ok;
}

Status coarsenVoxel(TaskSystem& tasks, const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides,
                    CutCellPoisson* coarse) {
  if (coarse == nullptr) return fail(Status::InvalidArgument, "multigrid coarsening: coarse is null");
  SlabPasses passes(tasks);
  CoarseningScratch scratch;
  appendCoarsenVoxel(fine, sides, coarse, &scratch, &passes);
  passes.runAll();
  return Status::Ok;
}

void appendCoarsenCutCell(const CutCellPoisson& fine, CutCellPoisson* coarse, CoarseningScratch* scratch,
                          SlabPasses* passes, const ChangedRows* fineChanged, ChangedRows* coarseChanged) {
  const CutCellPoisson* fp = &fine;
  passes->addStep([fp, coarse, scratch, passes, fineChanged, coarseChanged] {
    const Dims f(fp->grid);
    const bool freeSurface = !fp->liquidPhi.empty();
    const MacGridSpec spec = coarseGridSpec(fp->grid);
    const bool sameShape = sameGrid(coarse->grid, spec) && coarse->liquidPhi.empty() == !freeSurface &&
                           coarse->diagonal.size() == static_cast<size_t>(Dims(spec).cells());
    sizeCutCellPoisson(spec, freeSurface, false, coarse);
    const Dims c(coarse->grid);
    if (coarseChanged != nullptr) {
      coarseChanged->sizeFor(c.ny * c.nz);
      if (!sameShape || fineChanged == nullptr || fineChanged->all) coarseChanged->raiseAll();
    }
    // An update recomputes what the raised fine rows reach; otherwise everything is rebuilt.
    const bool update = coarseChanged != nullptr && !coarseChanged->all;
    ChangedRows* tracked = update ? coarseChanged : nullptr;
    uint8_t* todo = nullptr;
    scratch->dirichlet.resize(static_cast<size_t>(c.cells()));
    if (freeSurface) scratch->fluid.resize(static_cast<size_t>(c.cells()));
    if (update) {
      scratch->recompute.resize(static_cast<size_t>(c.ny * c.nz));
      todo = scratch->recompute.data();
      addRecomputedRowsPass(passes, f, c, fineChanged, coarseChanged, todo);
    }
    for (int a = 0; a < 3; ++a) {
      // Solids close a column, the free surface does not (its faces have coupling 0 only because
      // the air has no row; the coarse surface is placed by the free-surface passes).
      const Array<double>* open = freeSurface ? &fp->openFraction[a] : &fp->coupling[a];
      addCoarseFacePass(passes, f, c, a, &fp->coupling[a], open, &coarse->coupling[a], todo, tracked);
      if (freeSurface) addCoarseFacePass(passes, f, c, a, open, open, &coarse->openFraction[a], todo, tracked);
    }
    if (freeSurface) addCoarseFreeSurfacePasses(passes, fp, f, c, coarse, &scratch->fluid, todo, tracked);
    passes->addParallel(c.ny * c.nz, c.nx * kChildren, kRowGrain, [=](int64_t begin, int64_t end) {
      coarseDirichletRows(*fp, f, c, freeSurface, *coarse, begin, end, todo, scratch->dirichlet.data());
    });
    addCoarseDiagonalPasses(passes, c, coarse, scratch, todo, tracked);
  });
}

void appendCoarsenVoxel(const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides, CutCellPoisson* coarse,
                        CoarseningScratch* scratch, SlabPasses* passes) {
  const CutCellPoisson* fp = &fine;
  passes->addStep([fp, sides, coarse, scratch, passes] {
    const Dims f(fp->grid);
    // McAdams et al.'s labels: a coarse cell is air (Dirichlet) when any child is, else fluid
    // when any child is, else solid.
    const bool freeSurface = !fp->air.empty();
    sizeCutCellPoisson(coarseGridSpec(fp->grid), false, freeSurface, coarse);
    const Dims c(coarse->grid);
    scratch->dirichlet.resize(static_cast<size_t>(c.cells()));
    scratch->fluid.resize(static_cast<size_t>(c.cells()));
    uint8_t* fluid = scratch->fluid.data();
    addCellPass(passes, c, kChildren, [=](int64_t I, int64_t J, int64_t K) {
      bool anyFluid = false, anyAir = false;
      forEachChild(f, I, J, K, [&](int64_t child) {
        anyFluid = anyFluid || fp->diagonal[static_cast<size_t>(child)] > 0.0;
        anyAir = anyAir || (freeSurface && fp->air[static_cast<size_t>(child)] != 0);
      });
      const size_t cell = static_cast<size_t>(c.cell(I, J, K));
      fluid[cell] = anyFluid && !anyAir ? 1 : 0;
      if (freeSurface) coarse->air[cell] = anyAir ? 1 : 0;
    });
    // Only couplings between two fluid cells are set below.
    for (int a = 0; a < 3; ++a) {
      double* coupling = coarse->coupling[a].data();
      passes->addParallel(static_cast<int64_t>(coarse->coupling[a].size()), 1, 4096,
                          [coupling](int64_t begin, int64_t end) { std::fill(coupling + begin, coupling + end, 0.0); });
    }
    addCellPass(passes, c, 1, [=](int64_t I, int64_t J, int64_t K) {
      const int64_t C[3] = {I, J, K};
      const int64_t cell = c.cell(I, J, K);
      scratch->dirichlet[static_cast<size_t>(cell)] = 0.0;
      if (!fluid[cell]) return;
      double open = 0.0;
      for (int a = 0; a < 3; ++a) {
        if (C[a] == 0 && sides[2 * a] == DomainSide::Open) open += kVoxelCoupling;
        if (C[a] == c.along(a) - 1 && sides[2 * a + 1] == DomainSide::Open) open += kVoxelCoupling;
        // A face to an air neighbour is Dirichlet (p = 0 at the neighbour's centre).
        if (freeSurface && C[a] + 1 < c.along(a)) {
          int64_t high[3] = {I, J, K};
          ++high[a];
          if (coarse->air[static_cast<size_t>(c.cell(high[0], high[1], high[2]))]) open += kVoxelCoupling;
        }
        if (C[a] == 0) continue;
        int64_t low[3] = {I, J, K};
        --low[a];
        const size_t lowCell = static_cast<size_t>(c.cell(low[0], low[1], low[2]));
        if (fluid[lowCell]) coarse->coupling[a][static_cast<size_t>(c.face(a, I, J, K))] = kVoxelCoupling;
        else if (freeSurface && coarse->air[lowCell]) open += kVoxelCoupling;
      }
      scratch->dirichlet[static_cast<size_t>(cell)] = open;
    });
    addCoarseDiagonalPasses(passes, c, coarse, scratch);
  });
}

}  // namespace vp
