// The warp step of isosurface stuffing: lattice vertices too close to a cut point are moved
// onto it, so that no tet is filled between a lattice vertex and a cut point nearly on top of
// it. A cut point on edge vw violates v when it is closer to v than alpha times the edge's
// length (isosurface_stuffing.h: alpha for long and for short edges); a violated vertex goes
// to the nearest cut point it violates, becomes a surface vertex, and the cut points on its
// other edges are dropped.
//
// Order: a vertex whose nearest violated cut point lies on an edge to another violated vertex
// waits for that vertex. If that one warps, the shared edge's cut point is dropped and the
// waiting vertex no longer needs it; so no vertex sits on an edge whose other end was warped
// too. Warping both ends of such an edge, as a plain sweep in lattice order may, flattens the
// tets around it below the angle bound. A cycle of waiting vertices (rare) is broken at its
// lowest id.
#pragma once

#include "geometry/bcc_lattice.h"

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace vp {

struct CutPoint {
  int64_t inside = 0, outside = 0;  // lattice vertex ids of the edge's ends
  double t = 0.0;                   // from the inside end, as a fraction of the edge
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

// Lattice vertex -> index in `cuts` of the cut point it is warped onto. Deterministic.
std::unordered_map<int64_t, int32_t> warpLattice(const BccLattice& lattice, const std::vector<CutPoint>& cuts);

}  // namespace vp
