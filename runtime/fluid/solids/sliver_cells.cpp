// Sliver cells closed (see sliver_cells.h).
#include "fluid/solids/sliver_cells.h"

#include "fluid/solids/cell_box.h"

namespace vp {
namespace {

constexpr int kFaces = 6;

int64_t boxCellCount(const CellBox& b) {
  if (b.empty()) return 0;
  return static_cast<int64_t>(b.hi[0] - b.lo[0] + 1) * (b.hi[1] - b.lo[1] + 1) * (b.hi[2] - b.lo[2] + 1);
}

// One sweep over the box in cell order; returns the cells it closed.
int64_t closeSweep(const CellBox& b, FaceFractionField& f) {
  int64_t closed = 0;
  for (int k = b.lo[2]; k <= b.hi[2]; ++k)
    for (int j = b.lo[1]; j <= b.hi[1]; ++j)
      for (int i = b.lo[0]; i <= b.hi[0]; ++i) {
        const double sum = cellOpenSum(f, i, j, k);
        if (!(sum > 0.0) || sum >= kFaces * kSliverCellWeight) continue;
        for (int face = 0; face < kFaces; ++face) faceOpen(f, i, j, k, face) = 0.0;
        ++closed;
      }
  return closed;
}

}  // namespace

int64_t closeSliverCells(const Aabb& box, FaceFractionField* field) {
  const CellBox cells = cellBoxAround(field->grid, box, 0);
  if (box.empty() || cells.empty()) return 0;
  // A closed cell has no open face, so it is never closed again: each sweep that changes
  // something closes a cell for good, and the sweeps end.
  int64_t total = 0;
  for (int64_t closed = closeSweep(cells, *field); closed > 0; closed = closeSweep(cells, *field)) total += closed;
  return total;
}

void addSliverCellPasses(SlabPasses& passes, const Aabb& box, FaceFractionField* field) {
  const int64_t cells = box.empty() ? 0 : boxCellCount(cellBoxAround(field->grid, box, 0));
  if (cells == 0) return;
  passes.addWhole(cells, [box, field] { closeSliverCells(box, field); });
}

}  // namespace vp
