// The graded lattice of isosurface stuffing: coarser tets inside, as Labelle & Shewchuk 2007
// grade theirs, by this code's own transition tets (not the paper's red and bisected black
// ones; docs/choices.md, "Surface to tets"): a balanced octree over the cubes of a uniform BCC lattice (bcc_lattice.h) whose leaves are the
// lattice's own cubes near the surface and blocks of 2^l x 2^l x 2^l of them deep inside,
// filled with tets that conform across leaves of different sizes without hanging vertices.
//
// Leaves: a block of level l (aligned to multiples of 2^l cubes) becomes one leaf when every
// lattice vertex within kGradedMarginCubes cubes of it is inside and not warped, up to
// `maxCoarsening` levels;
// then leaves are split until every two leaves that touch (across a face, an edge or a corner)
// differ by at most one level. A vertex is a leaf's corner, or the centre of a leaf or of a
// face between leaves of two sizes; all of them are vertices of the uniform lattice.
//
// Tets, per face shared by two leaves:
// - the same size: the octahedron of the two centres and the face's boundary, cut around the
//   axis joining the centres into one tet per boundary segment (the face's edges split at every
//   leaf corner on them). For two finest cubes these are exactly the uniform lattice's tets.
// - a leaf and a larger one (the face is a quarter of the larger leaf's face): the two pyramids
//   from either centre over the face, whose base is cut by a diagonal, or fanned from the
//   face's centre when its edges carry more corners.
// Neighbouring pieces meet on triangles of a centre and one boundary segment, cut the same way
// from both sides, so the mesh conforms. Only the finest leaves' shared faces are left to the
// stencils; every other tet has all four vertices inside and unwarped (the margin), so they go
// to the output as they are.
#pragma once

#include "core/allocator.h"
#include "geometry/bcc_lattice.h"

#include <array>
#include <cstdint>
#include <functional>

namespace vp {

// Cubes of margin between a coarse leaf and any vertex that is not inside and unwarped: the
// finest cubes around a coarse leaf lend their centres and corners to its transition tets.
constexpr int kGradedMarginCubes = 1;
// The most levels of coarsening accepted (blocks of up to 2^8 cubes on a side).
constexpr int kMaxStuffingGrading = 8;

class GradedBccLattice {
 public:
  // `inside`: per lattice vertex id, > 0 inside and not warped. maxCoarsening 0 leaves every
  // cube a leaf.
  GradedBccLattice(const BccLattice& lattice, const Array<int8_t>& inside, int maxCoarsening);

  // The leaf level of the lattice cube (i, j, k).
  int level(int64_t i, int64_t j, int64_t k) const;
  int64_t leafCount() const { return leaves_; }

  // The uniform lattice's tets on faces between two finest cubes, in the uniform lattice's order
  // (bcc_lattice.h forEachTet, less the faces that touch a coarser leaf).
  void forEachFineTet(const std::function<void(const std::array<LatticePoint, 4>&)>& visit) const;
  // Every other tet, unoriented, in the order of the leaves' lowest cubes.
  void forEachCoarseTet(const std::function<void(const std::array<LatticePoint, 4>&)>& visit) const;

 private:
  int64_t cubeIndex(int64_t i, int64_t j, int64_t k) const { return (k * cubes_[1] + j) * cubes_[0] + i; }
  bool inCubes(int64_t i, int64_t j, int64_t k) const;
  bool isLeafCorner(const LatticePoint& d) const;  // d doubled, even coordinates
  void coarsen(const Array<int8_t>& inside, int maxCoarsening);
  bool balanceOnce();
  void countLeaves();
  // The face of the leaf at `anchor` (size s cubes) on side `dir` (0 low, 1 high) of `axis`.
  void visitFace(const std::array<int64_t, 3>& anchor, int64_t s, int axis, int dir,
                 const std::function<void(const std::array<LatticePoint, 4>&)>& visit) const;

  const BccLattice& lattice_;
  std::array<int64_t, 3> cubes_;
  Array<int8_t> level_;        // per cube
  Array<uint8_t> leafCorner_;  // per lattice corner
  int64_t leaves_ = 0;
};

}  // namespace vp
