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
