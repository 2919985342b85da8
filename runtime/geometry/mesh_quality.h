// What a simulation mesh is like, for the host to judge it: the range of its tets' dihedral
// angles (small ones make a stiff, badly conditioned system; near 180 degrees, slivers) and
// its volume against the volume of the surface it stands for (a mesher that swells thin parts
// makes the body heavier than its model).
#pragma once

#include "geometry/surface_mesh.h"
#include "geometry/tet_mesh.h"

namespace vp {

struct TetMeshQuality {
  double minDihedralDegrees = 0.0, maxDihedralDegrees = 0.0;
  double tetVolume = 0.0;      // the sum of the tets' volumes
  double surfaceVolume = 0.0;  // enclosed by `surface` (divergence theorem; outward triangles)
};

// The dihedral angle at each of a tet's six edges is the angle between the other two
// vertices seen along the edge. `mesh` positively oriented, indices in range.
TetMeshQuality tetMeshQuality(const TetMesh& mesh, const SurfaceMesh& surface);

// The smallest and largest dihedral angle (degrees) of the tet (a, b, c, d).
void tetDihedralRangeDegrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                             const Eigen::Vector3d& d, double* minDegrees, double* maxDegrees);

// The volume a closed, outward-oriented triangle surface encloses.
double enclosedVolume(const SurfaceMesh& surface);

}  // namespace vp
