#include "geometry/graded_bcc_lattice.h"

#include <algorithm>
#include <vector>

namespace vp {

GradedBccLattice::GradedBccLattice(const BccLattice& lattice, const Array<int8_t>& inside, int maxCoarsening)
    : lattice_(lattice), cubes_(lattice.cubes()) {
  level_.assign(static_cast<size_t>(cubes_[0] * cubes_[1] * cubes_[2]), 0);
  coarsen(inside, maxCoarsening);
  while (balanceOnce()) {
  }
  countLeaves();
}

int GradedBccLattice::level(int64_t i, int64_t j, int64_t k) const {
  return level_[static_cast<size_t>(cubeIndex(i, j, k))];
}

bool GradedBccLattice::inCubes(int64_t i, int64_t j, int64_t k) const {
  return i >= 0 && j >= 0 && k >= 0 && i < cubes_[0] && j < cubes_[1] && k < cubes_[2];
}

bool GradedBccLattice::isLeafCorner(const LatticePoint& d) const {
  return leafCorner_[static_cast<size_t>(lattice_.id(d))] != 0;
}

void GradedBccLattice::coarsen(const Array<int8_t>& inside, int maxCoarsening) {
  if (maxCoarsening <= 0) return;
  // A cube is clear when its eight corners and its centre are inside.
  Array<uint8_t> clear(level_.size(), 0);
  for (int64_t k = 0; k < cubes_[2]; ++k)
    for (int64_t j = 0; j < cubes_[1]; ++j)
      for (int64_t i = 0; i < cubes_[0]; ++i) {
        bool all = inside[static_cast<size_t>(lattice_.id({{2 * i + 1, 2 * j + 1, 2 * k + 1}}))] > 0;
        for (int c = 0; c < 8 && all; ++c)
          all = inside[static_cast<size_t>(
                    lattice_.id({{2 * (i + (c & 1)), 2 * (j + ((c >> 1) & 1)), 2 * (k + (c >> 2))}}))] > 0;
        clear[static_cast<size_t>(cubeIndex(i, j, k))] = all;
      }
  // Levels in increasing order: a block's sub-blocks pass whenever it does, so a finer level's
  // marks are overwritten only by the block containing them.
  for (int l = 1; l <= maxCoarsening; ++l) {
    const int64_t s = int64_t(1) << l, m = kGradedMarginCubes;
    for (int64_t bk = 0; bk * s < cubes_[2]; ++bk)
      for (int64_t bj = 0; bj * s < cubes_[1]; ++bj)
        for (int64_t bi = 0; bi * s < cubes_[0]; ++bi) {
          bool ok = true;
          for (int64_t k = bk * s - m; k < bk * s + s + m && ok; ++k)
            for (int64_t j = bj * s - m; j < bj * s + s + m && ok; ++j)
              for (int64_t i = bi * s - m; i < bi * s + s + m && ok; ++i)
                ok = inCubes(i, j, k) && clear[static_cast<size_t>(cubeIndex(i, j, k))];
          if (!ok) continue;
          for (int64_t k = bk * s; k < bk * s + s; ++k)
            for (int64_t j = bj * s; j < bj * s + s; ++j)
              for (int64_t i = bi * s; i < bi * s + s; ++i) level_[static_cast<size_t>(cubeIndex(i, j, k))] = int8_t(l);
        }
  }
}

// Splits every leaf that touches a leaf more than one level finer; true if any was split.
bool GradedBccLattice::balanceOnce() {
  bool split = false;
  for (int64_t k = 0; k < cubes_[2]; ++k)
    for (int64_t j = 0; j < cubes_[1]; ++j)
      for (int64_t i = 0; i < cubes_[0]; ++i) {
        const int l = level(i, j, k);
        const int64_t s = int64_t(1) << l;
        if (l == 0 || i % s != 0 || j % s != 0 || k % s != 0) continue;
        bool unbalanced = false;
        for (int64_t z = k - 1; z <= k + s && !unbalanced; ++z)
          for (int64_t y = j - 1; y <= j + s && !unbalanced; ++y)
            for (int64_t x = i - 1; x <= i + s && !unbalanced; ++x)
              unbalanced = inCubes(x, y, z) && level(x, y, z) < l - 1;
        if (!unbalanced) continue;
        for (int64_t z = k; z < k + s; ++z)
          for (int64_t y = j; y < j + s; ++y)
            for (int64_t x = i; x < i + s; ++x) level_[static_cast<size_t>(cubeIndex(x, y, z))] = int8_t(l - 1);
        split = true;
      }
  return split;
}

void GradedBccLattice::countLeaves() {
  leafCorner_.assign(static_cast<size_t>(lattice_.cornerCount()), 0);
  leaves_ = 0;
  for (int64_t k = 0; k < cubes_[2]; ++k)
    for (int64_t j = 0; j < cubes_[1]; ++j)
      for (int64_t i = 0; i < cubes_[0]; ++i) {
        const int64_t s = int64_t(1) << level(i, j, k);
        if (i % s != 0 || j % s != 0 || k % s != 0) continue;
        ++leaves_;
        for (int c = 0; c < 8; ++c)
          leafCorner_[static_cast<size_t>(lattice_.id(
              {{2 * (i + s * (c & 1)), 2 * (j + s * ((c >> 1) & 1)), 2 * (k + s * (c >> 2))}}))] = 1;
      }
}

void GradedBccLattice::forEachFineTet(const std::function<void(const std::array<LatticePoint, 4>&)>& visit) const {
  for (int64_t k = 0; k < cubes_[2]; ++k)
    for (int64_t j = 0; j < cubes_[1]; ++j)
      for (int64_t i = 0; i < cubes_[0]; ++i) {
        if (level(i, j, k) != 0) continue;
        const std::array<int64_t, 3> c{{i, j, k}};
        for (int axis = 0; axis < 3; ++axis) {
          std::array<int64_t, 3> n = c;
          ++n[axis];
          // Past the lattice's last cube forEachTetAcross adds nothing, as in the uniform order.
          if (inCubes(n[0], n[1], n[2]) && level(n[0], n[1], n[2]) != 0) continue;
          lattice_.forEachTetAcross({{2 * i + 1, 2 * j + 1, 2 * k + 1}}, axis, visit);
        }
      }
}

void GradedBccLattice::forEachCoarseTet(const std::function<void(const std::array<LatticePoint, 4>&)>& visit) const {
  for (int64_t k = 0; k < cubes_[2]; ++k)
    for (int64_t j = 0; j < cubes_[1]; ++j)
      for (int64_t i = 0; i < cubes_[0]; ++i) {
        const int64_t s = int64_t(1) << level(i, j, k);
        if (i % s != 0 || j % s != 0 || k % s != 0) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int dir = 0; dir < 2; ++dir) visitFace({{i, j, k}}, s, axis, dir, visit);
      }
}

void GradedBccLattice::visitFace(const std::array<int64_t, 3>& anchor, int64_t s, int axis, int dir,
                                 const std::function<void(const std::array<LatticePoint, 4>&)>& visit) const {
  std::array<int64_t, 3> across = anchor;
  across[axis] = dir == 0 ? anchor[axis] - 1 : anchor[axis] + s;
  if (!inCubes(across[0], across[1], across[2])) return;
  const int l = level(anchor[0], anchor[1], anchor[2]);
  const int ln = level(across[0], across[1], across[2]);
  // Same size: once, from the lower leaf, and the finest pairs are the stencils'. Smaller
  // neighbours: theirs to fill.
  const bool same = ln == l && dir == 1 && l > 0, larger = ln == l + 1;
  if (!same && !larger) return;

  const LatticePoint centre{{2 * anchor[0] + s, 2 * anchor[1] + s, 2 * anchor[2] + s}};
  LatticePoint other;
  const int64_t sn = int64_t(1) << ln;
  for (int a = 0; a < 3; ++a) other[a] = 2 * (across[a] - across[a] % sn) + sn;

  // The face's boundary, counter-clockwise in (b, e), with every leaf corner on its edges.
  const int b = (axis + 1) % 3, e = (axis + 2) % 3;
  const int64_t plane = 2 * (dir == 0 ? anchor[axis] : anchor[axis] + s);
  const int64_t walk[4][2][2] = {{{0, 0}, {1, 0}}, {{1, 0}, {1, 1}}, {{1, 1}, {0, 1}}, {{0, 1}, {0, 0}}};
  std::vector<LatticePoint> ring;
  for (const auto& side : walk)
    for (int64_t t = 0; t < s; ++t) {
      LatticePoint p;
      p[axis] = plane;
      p[b] = 2 * (anchor[b] + s * side[0][0] + t * (side[1][0] - side[0][0]));
      p[e] = 2 * (anchor[e] + s * side[0][1] + t * (side[1][1] - side[0][1]));
      if (t == 0 || isLeafCorner(p)) ring.push_back(p);
    }
  const size_t m = ring.size();
  if (same) {
    for (size_t r = 0; r < m; ++r) visit({{centre, other, ring[r], ring[(r + 1) % m]}});
    return;
  }
  for (const LatticePoint& apex : {centre, other}) {
    if (m == 4) {
      visit({{apex, ring[0], ring[1], ring[2]}});
      visit({{apex, ring[0], ring[2], ring[3]}});
      continue;
    }
    LatticePoint mid;
    mid[axis] = plane;
    mid[b] = 2 * anchor[b] + s;
    mid[e] = 2 * anchor[e] + s;
    for (size_t r = 0; r < m; ++r) visit({{apex, mid, ring[r], ring[(r + 1) % m]}});
  }
}

}  // namespace vp
