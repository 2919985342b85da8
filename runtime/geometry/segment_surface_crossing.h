// Where a segment first crosses a triangle surface: the cut points of isosurface stuffing,
// found against the exact surface rather than by interpolating sampled distances.
#pragma once

#include "geometry/refit_bvh.h"
#include "geometry/surface_mesh.h"

#include <Eigen/Core>

namespace vp {

// The smallest t in [0, 1] at which a + t (b - a) meets a triangle of `surface` (`bvh` built
// over it). A hit within a relative 1e-9 of a triangle's edges or of the segment's ends
// counts, so a segment through a shared edge or ending on the surface is not missed by
// round-off. Returns false when nothing is met (the segment lies in a triangle's plane).
bool firstSurfaceCrossing(const RefitBvh& bvh, const SurfaceMesh& surface, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& b, double* t);

}  // namespace vp
