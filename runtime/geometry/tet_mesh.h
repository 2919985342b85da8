// A linear tetrahedral mesh: the input to every deformable actor and the output of the
// importers and the voxel tetrahedralizer.
//
// Orientation convention (used everywhere in VolPhys): a tet {a, b, c, d} is positively
// oriented when (b - a) . ((c - a) x (d - a)) > 0. validateAndRepairTetMesh() enforces it.
#pragma once

#include "core/allocator.h"

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross()

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vp {

struct TetMesh {
  Array<Eigen::Vector3d> vertices;
  // int32 because the simulation kernels index plain arrays with 32-bit ints (and the same
  // bodies run in CUDA); the validator rejects meshes that do not fit.
  Array<std::array<int32_t, 4>> tets;
};

// Signed volume of the tet (a, b, c, d); positive for the orientation convention above.
inline double signedTetVolume(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

// Signed volume of tet `t`; the caller guarantees its indices are in range.
double signedTetVolume(const TetMesh& mesh, size_t t);

// Sum of signed tet volumes (the mesh's volume once every tet is positively oriented).
double totalVolume(const TetMesh& mesh);

// Mean length of the 6 edges of every tet (edges shared by several tets count once per
// tet). Used to scale tolerances so they do not depend on the mesh's units. Indices must
// be in range; returns 0 for a mesh without tets.
double meanTetEdgeLength(const TetMesh& mesh);

// The 4 triangular faces of a tet, each listed so that its normal (by the right-hand rule)
// points out of a positively oriented tet. Face f is opposite local vertex f.
constexpr std::array<std::array<int, 3>, 4> kTetFaces = {{
    {{1, 2, 3}}, {{0, 3, 2}}, {{0, 1, 3}}, {{0, 2, 1}}}};

}  // namespace vp
