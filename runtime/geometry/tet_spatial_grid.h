// A uniform grid over the bounding boxes of a tet mesh's tets: answers "which tets may
// contain this point" and "visit cells in growing rings around this point" in O(1) per cell.
//
// Why a uniform grid and not a BVH: simulation meshes (voxel-made or imported) have tets of
// similar size, which is the case a uniform grid handles best, and it is 100 lines with no
// dependency. Cells are sized from the mean tet bounding box, so each tet lands in a few
// cells and each cell holds a few tets.
#pragma once

#include "core/allocator.h"
#include "geometry/tet_mesh.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstdint>
#include <vector>

namespace vp {

class TetSpatialGrid {
 public:
  // The mesh must have valid indices; it is not retained.
  void build(const TetMesh& mesh);

  // Cell coordinates of `p`, clamped into the grid.
  std::array<int64_t, 3> cellOf(const Eigen::Vector3d& p) const;
  // Tets whose bounding box overlaps cell (i, j, k); the cell must be in the grid.
  template <class Visit>
  void forEachTetInCell(const std::array<int64_t, 3>& c, Visit visit) const {
    const int64_t cell = (c[2] * cells_[1] + c[1]) * cells_[0] + c[0];
    for (int64_t n = cellStart_[cell]; n < cellStart_[cell + 1]; ++n) visit(tets_[n]);
  }

  // Calls visit(cell) for every grid cell at Chebyshev distance exactly `ring` from
  // `centre`. Returns false when no such cell exists (the ring lies outside the grid).
  template <class Visit>
  bool forEachCellInRing(const std::array<int64_t, 3>& centre, int64_t ring, Visit visit) const {
    bool any = false;
    std::array<int64_t, 3> lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max<int64_t>(0, centre[a] - ring);
      hi[a] = std::min<int64_t>(cells_[a] - 1, centre[a] + ring);
    }
    for (int64_t k = lo[2]; k <= hi[2]; ++k)
      for (int64_t j = lo[1]; j <= hi[1]; ++j) {
        if (std::max(std::abs(j - centre[1]), std::abs(k - centre[2])) == ring) {
          for (int64_t i = lo[0]; i <= hi[0]; ++i) visit(std::array<int64_t, 3>{{i, j, k}});
          any = true;
        } else {  // inside the ring's yz extent only the two x ends are on the ring
          if (centre[0] - ring >= 0) {
            visit(std::array<int64_t, 3>{{centre[0] - ring, j, k}});
            any = true;
          }
          if (centre[0] + ring < cells_[0]) {
            visit(std::array<int64_t, 3>{{centre[0] + ring, j, k}});
            any = true;
          }
        }
      }
    return any;
  }

  // A lower bound on the distance from `p` to any point of a cell at Chebyshev distance
  // > `ring` from `centre` (infinity if there is no such cell).
  double distanceBeyondRing(const Eigen::Vector3d& p, const std::array<int64_t, 3>& centre, int64_t ring) const;

  double cellSize() const { return cellSize_; }

 private:
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cellSize_ = 1.0;
  std::array<int64_t, 3> cells_{{1, 1, 1}};
  Array<int64_t> cellStart_;  // CSR: tets of cell c are tets_[cellStart_[c] .. cellStart_[c+1])
  Array<int32_t> tets_;
};

}  // namespace vp
