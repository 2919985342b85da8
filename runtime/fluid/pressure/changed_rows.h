// Which grid rows (j + ny k) of a pressure operator level changed since the multigrid levels
// built from it were last brought up to date (poisson_multigrid.h), so that an update
// recomputes only what those rows reach instead of rebuilding every level.
//
// A row is raised when any value the cut-cell coarsening reads there changed bit for bit: the
// diagonal, the free-surface part of the diagonal, and the couplings and open fractions of the
// faces the row owns (a cell row owns the faces on the low side of its cells along y and z and
// every x face of the row; the faces on the grid's high y and z sides, always closed, belong to
// the last row). The level set is not tracked: it moves wherever the liquid moves, and the
// coarsening reads it only through passes that run over every cell anyway.
//
// Flags are raised by the builders as they write and cleared only when an update has
// completed, so an update stopped between slices leaves every change it has not yet consumed
// (and the ones it made to coarser levels) raised for the next one.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/allocator.h"
#include "gpu_kernels/kernel_support.h"

namespace vp {

struct ChangedRows {
  Array<uint8_t> row;  // per grid row: 1 when changed
  bool all = true;     // everything changed (nothing built yet, or the grid's shape changed)

  // Sizes the flags for `rows` rows; a change of size raises everything.
  void sizeFor(int64_t rows) {
    if (row.size() == static_cast<size_t>(rows)) return;
    row.assign(static_cast<size_t>(rows), 0);
    all = true;
  }
  void raiseAll() { all = true; }
  // From concurrent writers of one pass (kernels::raiseSharedFlag).
  void raise(int64_t r) { kernels::raiseSharedFlag(&row[static_cast<size_t>(r)]); }
  bool raised(int64_t r) const { return all || row[static_cast<size_t>(r)] != 0; }
  bool any() const { return all || std::any_of(row.begin(), row.end(), [](uint8_t f) { return f != 0; }); }
  void clear() {
    std::fill(row.begin(), row.end(), uint8_t{0});
    all = false;
  }
};

// The cell row owning face row `faceRow` of axis a on a grid of ny x nz cell rows (face rows
// are the lines of faces along x: ny x nz of them for a = 0, (ny + 1) x nz for a = 1, ny x
// (nz + 1) for a = 2): the row of the face's high cell, the last row for the high domain side.
inline int64_t owningRow(int a, int64_t faceRow, int64_t ny, int64_t nz) {
  if (a == 0) return faceRow;
  if (a == 1) return std::min(faceRow % (ny + 1), ny - 1) + ny * (faceRow / (ny + 1));
  return faceRow % ny + ny * std::min(faceRow / ny, nz - 1);
}

// The face rows of axis a that cell row `row` owns (owningRow's inverse): row[0 .. count).
struct OwnedFaceRows {
  int64_t row[2];
  int count;
};
inline OwnedFaceRows ownedFaceRows(int a, int64_t row, int64_t ny, int64_t nz) {
  const int64_t j = row % ny, k = row / ny;
  if (a == 0) return OwnedFaceRows{{row, -1}, 1};
  if (a == 1) return OwnedFaceRows{{j + (ny + 1) * k, j + 1 + (ny + 1) * k}, j + 1 == ny ? 2 : 1};
  return OwnedFaceRows{{row, row + ny}, k + 1 == nz ? 2 : 1};
}

// Whether two doubles have the same bits (0.0 and -0.0 differ; a change of sign can change
// what is computed from the value).
inline bool sameBits(double a, double b) {
  uint64_t x, y;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

// *slot = value, raising row `r` of `changed` (when given) where the bits differ.
inline void storeTracked(double* slot, double value, ChangedRows* changed, int64_t r) {
  if (changed != nullptr && !sameBits(*slot, value)) changed->raise(r);
  *slot = value;
}

}  // namespace vp
