// Cut-cell and voxel coarsening of the pressure operator (see multigrid_coarsening.h).
#include "fluid/multigrid_coarsening.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/parallel_for.h"
#include "fluid/free_surface.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 16;
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
};

void sizeLevel(const MacGridSpec& spec, CutCellPoisson* op) {
  const Dims d(spec);
  op->grid = spec;
  op->coupling[0].assign(static_cast<size_t>((d.nx + 1) * d.ny * d.nz), 0.0);
  op->coupling[1].assign(static_cast<size_t>(d.nx * (d.ny + 1) * d.nz), 0.0);
  op->coupling[2].assign(static_cast<size_t>(d.nx * d.ny * (d.nz + 1)), 0.0);
  op->diagonal.assign(static_cast<size_t>(d.cells()), 0.0);
  op->air.clear();
  op->liquidPhi.clear();
  op->surfaceDirichlet.clear();
  for (auto& open : op->openFraction) open.clear();
}

// Diagonal = couplings of the six faces + Dirichlet part; couplings must be set.
void assembleDiagonal(TaskSystem& tasks, const std::vector<double>& dirichlet, CutCellPoisson* op) {
  const Dims d(op->grid);
  parallelFor(tasks, d.ny * d.nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t j = row % d.ny, k = row / d.ny;
      for (int64_t i = 0; i < d.nx; ++i) {
        const int64_t c = d.cell(i, j, k);
        double sum = 0.0;
        for (int a = 0; a < 3; ++a) {
          int64_t hi[3] = {i, j, k};
          ++hi[a];
          sum += op->coupling[a][static_cast<size_t>(d.face(a, i, j, k))];
          sum += op->coupling[a][static_cast<size_t>(d.face(a, hi[0], hi[1], hi[2]))];
        }
        op->diagonal[static_cast<size_t>(c)] = sum + dirichlet[static_cast<size_t>(c)];
      }
    }
  });
}

// Calls visit(child cell index) for the children of coarse cell (I, J, K) that exist.
template <class Visit>
void forEachChild(const Dims& fine, int64_t I, int64_t J, int64_t K, const Visit& visit) {
  for (int64_t k = 2 * K; k < 2 * K + 2 && k < fine.nz; ++k)
    for (int64_t j = 2 * J; j < 2 * J + 2 && j < fine.ny; ++j)
      for (int64_t i = 2 * I; i < 2 * I + 2 && i < fine.nx; ++i) visit(fine.cell(i, j, k));
}

// Calls visit(I, J, K) for every cell of grid d, in parallel over its rows.
template <class Visit>
void forEachCell(TaskSystem& tasks, const Dims& d, const Visit& visit) {
  parallelFor(tasks, d.ny * d.nz, kRowGrain, [&](int64_t begin, int64_t end) {
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
void coarsenFaces(TaskSystem& tasks, const Dims& f, const Dims& c, int a, const std::vector<double>& in,
                  const std::vector<double>& inner, std::vector<double>* outValues) {
  const int b = (a + 1) % 3, e = (a + 2) % 3;
  const int64_t fineB = f.along(b), fineE = f.along(e);
  std::vector<double>& out = *outValues;
  out.assign(static_cast<size_t>(a == 0 ? (c.nx + 1) * c.ny * c.nz
                                 : a == 1 ? c.nx * (c.ny + 1) * c.nz : c.nx * c.ny * (c.nz + 1)), 0.0);
  // Neighbouring faces along a are `stride` apart in every face layout.
  const int64_t stride = a == 0 ? 1 : a == 1 ? f.nx : f.nx * f.ny;
  forEachCell(tasks, c, [&](int64_t I, int64_t J, int64_t K) {
    const int64_t C[3] = {I, J, K};
    if (C[a] == 0) return;
    // 2I + 1 is the domain face when the coarse cell has one child along a.
    const bool behindHigh = 2 * C[a] + 1 < f.along(a);
    double sum = 0.0;
    for (int64_t e2 = 2 * C[e]; e2 < 2 * C[e] + 2 && e2 < fineE; ++e2)
      for (int64_t b2 = 2 * C[b]; b2 < 2 * C[b] + 2 && b2 < fineB; ++b2) {
        int64_t x[3];
        x[a] = 2 * C[a];
        x[b] = b2;
        x[e] = e2;
        const int64_t face = f.face(a, x[0], x[1], x[2]);
        const double shared = in[static_cast<size_t>(face)];
        const double low = inner[static_cast<size_t>(face - stride)];
        const double high = behindHigh ? inner[static_cast<size_t>(face + stride)] : 1.0;
        if (!(shared > 0.0 && low > 0.0 && high > 0.0)) continue;
        sum += behindHigh ? 2.0 / (0.5 / low + 1.0 / shared + 0.5 / high) : 1.5 / (0.5 / low + 1.0 / shared);
      }
    out[static_cast<size_t>(c.face(a, I, J, K))] = 0.5 * sum;
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
// coarse spacing, so the coarse surface lies too high by a depth that grows with the level: at
// 64^3 with the surface at y = 0.61 the level-1 cells under it summed to theta 0.54 where their
// centres lie 0.02 of a cell below the surface. Iterations to 1e-6 on the liquid tank without
// colliders, 64/128^3: 7/7 summed, 6/6 placed again.
// Where no such face exists (air pockets smaller than the coarse cell), the summed rule stays.
void coarsenFreeSurface(TaskSystem& tasks, const CutCellPoisson& fine, const Dims& f, const Dims& c,
                        CutCellPoisson* coarse) {
  coarse->liquidPhi.assign(static_cast<size_t>(c.cells()), 0.0);
  coarse->surfaceDirichlet.assign(static_cast<size_t>(c.cells()), 0.0);
  std::vector<uint8_t> fluid(static_cast<size_t>(c.cells()), 0);
  forEachCell(tasks, c, [&](int64_t I, int64_t J, int64_t K) {
    double phi = 0.0;
    int children = 0;
    bool anyFluid = false;
    forEachChild(f, I, J, K, [&](int64_t child) {
      phi += fine.liquidPhi[static_cast<size_t>(child)];
      ++children;
      anyFluid = anyFluid || fine.diagonal[static_cast<size_t>(child)] > 0.0;
    });
    const size_t cell = static_cast<size_t>(c.cell(I, J, K));
    coarse->liquidPhi[cell] = phi / children;
    fluid[cell] = anyFluid ? 1 : 0;
  });
  forEachCell(tasks, c, [&](int64_t I, int64_t J, int64_t K) {
    const size_t cell = static_cast<size_t>(c.cell(I, J, K));
    if (!fluid[cell]) return;
    const double phi = coarse->liquidPhi[cell];
    double surface = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        int64_t nb[3] = {I, J, K};
        nb[a] += side == 0 ? -1 : 1;
        if (nb[a] < 0 || nb[a] >= c.along(a)) continue;
        const size_t nbCell = static_cast<size_t>(c.cell(nb[0], nb[1], nb[2]));
        if (fluid[nbCell]) continue;
        int64_t high[3] = {I, J, K};
        high[a] += side;
        const double open = coarse->openFraction[a][static_cast<size_t>(c.face(a, high[0], high[1], high[2]))];
        if (!(open > 0.0)) continue;
        const double phiNb = coarse->liquidPhi[nbCell];
        // A liquid neighbour mean without fluid children is air over solid: surface at its centre.
        const double theta = !isLiquid(phi) ? kMinFreeSurfaceTheta
                             : isLiquid(phiNb) ? 1.0 : freeSurfaceTheta(phi, phiNb);
        surface += open / theta;
      }
    if (!(surface > 0.0)) {
      forEachChild(f, I, J, K, [&](int64_t child) { surface += fine.surfaceDirichlet[static_cast<size_t>(child)]; });
      surface *= 0.5;
    }
    coarse->surfaceDirichlet[cell] = surface;
  });
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
  const Dims f(fine.grid);
  sizeLevel(coarseGridSpec(fine.grid), coarse);
  const Dims c(coarse->grid);
  const bool freeSurface = !fine.liquidPhi.empty();
  for (int a = 0; a < 3; ++a) {
    // Solids close a column, the free surface does not (its faces have coupling 0 only because
    // the air has no row; the coarse surface is placed by coarsenFreeSurface).
    const std::vector<double>& open = freeSurface ? fine.openFraction[a] : fine.coupling[a];
    coarsenFaces(tasks, f, c, a, fine.coupling[a], open, &coarse->coupling[a]);
    if (freeSurface) coarsenFaces(tasks, f, c, a, open, open, &coarse->openFraction[a]);
  }
  std::vector<double> dirichlet(static_cast<size_t>(c.cells()), 0.0);
  forEachCell(tasks, c, [&](int64_t I, int64_t J, int64_t K) {
    double sum = 0.0;
    // The free-surface part is placed again at this level's spacing below.
    forEachChild(f, I, J, K, [&](int64_t child) {
      const double part = dirichletPart(fine, child);
      sum += freeSurface ? std::max(0.0, part - fine.surfaceDirichlet[static_cast<size_t>(child)]) : part;
    });
    dirichlet[static_cast<size_t>(c.cell(I, J, K))] = 0.5 * sum;
  });
  if (freeSurface) {
    coarsenFreeSurface(tasks, fine, f, c, coarse);
    for (size_t cell = 0; cell < dirichlet.size(); ++cell) dirichlet[cell] += coarse->surfaceDirichlet[cell];
  }
  assembleDiagonal(tasks, dirichlet, coarse);
  labelFluidRegions(coarse);
  computeRowSpans(tasks, coarse);
  return Status::Ok;
}

Status coarsenVoxel(TaskSystem& tasks, const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides,
                    CutCellPoisson* coarse) {
  if (coarse == nullptr) return fail(Status::InvalidArgument, "multigrid coarsening: coarse is null");
  const Dims f(fine.grid);
  sizeLevel(coarseGridSpec(fine.grid), coarse);
  const Dims c(coarse->grid);
  // McAdams et al.'s labels: a coarse cell is air (Dirichlet) when any child is, else fluid
  // when any child is, else solid.
  const bool freeSurface = !fine.air.empty();
  std::vector<uint8_t> fluid(static_cast<size_t>(c.cells()), 0);
  if (freeSurface) coarse->air.assign(static_cast<size_t>(c.cells()), 0);
  else coarse->air.clear();
  parallelFor(tasks, c.ny * c.nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t J = row % c.ny, K = row / c.ny;
      for (int64_t I = 0; I < c.nx; ++I) {
        bool anyFluid = false, anyAir = false;
        forEachChild(f, I, J, K, [&](int64_t child) {
          anyFluid = anyFluid || fine.diagonal[static_cast<size_t>(child)] > 0.0;
          anyAir = anyAir || (freeSurface && fine.air[static_cast<size_t>(child)] != 0);
        });
        const size_t cell = static_cast<size_t>(c.cell(I, J, K));
        fluid[cell] = anyFluid && !anyAir ? 1 : 0;
        if (anyAir) coarse->air[cell] = 1;
      }
    }
  });
  std::vector<double> dirichlet(static_cast<size_t>(c.cells()), 0.0);
  parallelFor(tasks, c.ny * c.nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t J = row % c.ny, K = row / c.ny;
      for (int64_t I = 0; I < c.nx; ++I) {
        const int64_t C[3] = {I, J, K};
        const int64_t cell = c.cell(I, J, K);
        if (!fluid[static_cast<size_t>(cell)]) continue;
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
        dirichlet[static_cast<size_t>(cell)] = open;
      }
    }
  });
  assembleDiagonal(tasks, dirichlet, coarse);
  labelFluidRegions(coarse);
  computeRowSpans(tasks, coarse);
  return Status::Ok;
}

}  // namespace vp
