// The device pressure solve's view of a CPU-built hierarchy (see device_pressure_view.h).
#include "fluid/pressure/device_pressure_view.h"

#include <algorithm>

#include "fluid/pressure/poisson_rows.h"

namespace vp {
namespace {

gpu::RegionView regionView(const CutCellPoisson& op) {
  gpu::RegionView v;
  v.region = op.region.data();
  v.floating = op.regionFloating.data();
  v.cellCount = op.regionCellCount.data();
  v.count = static_cast<int64_t>(op.regionFloating.size());
  v.anyFloating = std::any_of(op.regionFloating.begin(), op.regionFloating.end(), [](uint8_t f) { return f != 0; });
  return v;
}

}  // namespace

Status makePressureSolveView(const CutCellPoisson& fine, const PoissonMultigrid& mg, gpu::PressureSolveView* view) {
  if (view == nullptr) return fail(Status::InvalidArgument, "pressure solve view: output is null");
  if (mg.settings.smoother != PoissonSmoother::RedBlackGaussSeidel)
    return fail(Status::InvalidArgument,
                "pressure solve view: multigrid smoother = DampedJacobi has no device path (red-black only)");
  if (mg.single.empty() || mg.single.front().diagonal.size() != fine.diagonal.size())
    return fail(Status::InvalidArgument, "pressure solve view: the multigrid was not built for this operator");
  *view = gpu::PressureSolveView{};
  view->fine = poisson_rows::Stencil<double>(fine);
  view->fineRegions = regionView(fine);
  view->sides = mg.sides;
  view->sweeps = mg.settings.sweeps;
  view->coarsestSweeps = mg.settings.coarsestSweeps;
  view->boundarySweeps = mg.settings.boundarySweeps;
  const int levels = mg.levelCount();
  for (int l = 0; l < levels; ++l) {
    const size_t at = static_cast<size_t>(l);
    gpu::MultigridLevelView level;
    level.op = poisson_rows::Stencil<float>(mg.single[at]);
    if (l + 1 < levels) level.prolongScale = mg.prolongScale[at].data();
    if (l > 0) level.regions = regionView(mg.coarse[at - 1]);
    const BoundaryCellLists& lists = mg.boundaryCells[at];
    for (int c = 0; c < 2; ++c) {
      level.boundary[c] = lists.byColour[static_cast<size_t>(c)].data();
      level.boundaryCount[c] = static_cast<int64_t>(lists.byColour[static_cast<size_t>(c)].size());
    }
    level.boundaryReads = lists.reads.data();
    view->levels.push_back(level);
  }
  return Status::Ok;
}

Status makeProjectionView(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& fine,
                          const PoissonMultigrid& multigrid, const double* liquidPhi, gpu::ProjectionView* view) {
  if (view == nullptr) return fail(Status::InvalidArgument, "projection view: output is null");
  if (!sameGrid(grid.spec, fractions.grid) || !sameGrid(grid.spec, fine.grid))
    return fail(Status::InvalidArgument, "projection view: the fractions or the operator belong to another grid");
  *view = gpu::ProjectionView{};
  VP_TRY(makePressureSolveView(fine, multigrid, &view->solve));
  view->fractions = netOutflowFields(grid, fractions);
  view->h = grid.spec.h;
  view->liquidPhi = liquidPhi;
  return Status::Ok;
}

}  // namespace vp
