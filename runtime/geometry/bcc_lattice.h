// The body-centred cubic lattice of isosurface stuffing: the corners and the centres of a
// block of cubes. Its tetrahedra each span two neighbouring cube centres and one edge of the
// face the two cubes share (12 per cube, all congruent). Each has two long edges of the cube's
// size h (centre-centre and the cube edge, opposite each other) and four short ones of
// h sqrt(3) / 2 (corner-centre).
//
// Vertices are named by "doubled" coordinates D: a corner with cube-corner index (i, j, k) is
// (2i, 2j, 2k), the centre of cube (i, j, k) is (2i + 1, 2j + 1, 2k + 1), so a vertex sits at
// origin + D h / 2. Ids: corners first, then centres, each in x-fastest order.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace vp {

using LatticePoint = std::array<int64_t, 3>;  // doubled coordinates

class BccLattice {
 public:
  // `cubes` cubes along each axis, of edge `h`, cube (0, 0, 0)'s min corner at `origin`.
  BccLattice(const Eigen::Vector3d& origin, double h, const std::array<int64_t, 3>& cubes);

  int64_t cornerCount() const { return (cubes_[0] + 1) * (cubes_[1] + 1) * (cubes_[2] + 1); }
  int64_t vertexCount() const { return cornerCount() + cubes_[0] * cubes_[1] * cubes_[2]; }
  const Eigen::Vector3d& origin() const { return origin_; }
  double spacing() const { return h_; }
  const std::array<int64_t, 3>& cubes() const { return cubes_; }

  LatticePoint point(int64_t id) const;
  // -1 when D is outside the lattice (or mixes even and odd coordinates).
  int64_t id(const LatticePoint& d) const;
  Eigen::Vector3d position(const LatticePoint& d) const;
  Eigen::Vector3d position(int64_t id) const { return position(point(id)); }

  // The 14 neighbours of D that exist, in a fixed order: the 6 along the axes (long edges),
  // then the 8 across the diagonals (short edges). visit(neighbour id, neighbour D).
  template <class Visit>
  void forEachNeighbour(const LatticePoint& d, const Visit& visit) const {
    for (const LatticePoint& step : kNeighbourSteps) {
      const LatticePoint n{{d[0] + step[0], d[1] + step[1], d[2] + step[2]}};
      const int64_t nid = id(n);
      if (nid >= 0) visit(nid, n);
    }
  }

  // Every tetrahedron once, as (centre, next centre along an axis, the two corners of one edge
  // of their shared face), in a fixed order: centres by id, axes x, y, z, the face's four
  // edges around it. visit(std::array<LatticePoint, 4>).
  template <class Visit>
  void forEachTet(const Visit& visit) const {
    for (int64_t k = 0; k < cubes_[2]; ++k)
      for (int64_t j = 0; j < cubes_[1]; ++j)
        for (int64_t i = 0; i < cubes_[0]; ++i)
          for (int axis = 0; axis < 3; ++axis) forEachTetAcross({{2 * i + 1, 2 * j + 1, 2 * k + 1}}, axis, visit);
  }

  // The four tetrahedra around the long edge from centre c to the next centre along `axis`
  // (none when that centre is outside the lattice).
  template <class Visit>
  void forEachTetAcross(const LatticePoint& c, int axis, const Visit& visit) const {
    LatticePoint next = c;
    next[axis] += 2;
    if (next[axis] > 2 * cubes_[axis]) return;
    const int b = (axis + 1) % 3, e = (axis + 2) % 3;
    const int64_t around[5][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}};
    for (int s = 0; s < 4; ++s) {
      LatticePoint p = c, q = c;
      p[axis] = q[axis] = c[axis] + 1;
      p[b] += around[s][0], p[e] += around[s][1];
      q[b] += around[s + 1][0], q[e] += around[s + 1][1];
      visit(std::array<LatticePoint, 4>{{c, next, p, q}});
    }
  }

  // Long edges join two corners or two centres; short edges a corner and a centre.
  static bool isLongEdge(const LatticePoint& a, const LatticePoint& b) { return (a[0] - b[0]) % 2 == 0; }

 private:
  static constexpr LatticePoint kNeighbourSteps[14] = {
      {{-2, 0, 0}}, {{2, 0, 0}}, {{0, -2, 0}}, {{0, 2, 0}}, {{0, 0, -2}}, {{0, 0, 2}},
      {{-1, -1, -1}}, {{1, -1, -1}}, {{-1, 1, -1}}, {{1, 1, -1}},
      {{-1, -1, 1}}, {{1, -1, 1}}, {{-1, 1, 1}}, {{1, 1, 1}}};

  Eigen::Vector3d origin_;
  double h_;
  std::array<int64_t, 3> cubes_;
};

}  // namespace vp
