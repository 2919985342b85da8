// A triangle mesh of a collider's shape in its local frame, for hosts to draw or export
// (vpColliderGetShapeMesh). It is a picture, not geometry the simulation uses: round shapes
// are tessellated, and a plane (unbounded) becomes a finite square.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "collide/collider_desc.h"

namespace vp {

struct ShapeDisplayMesh {
  Array<Vec3> positions;
  Array<Vec3> normals;  // per vertex, unit, pointing out of the solid
  Array<std::array<int32_t, 3>> triangles;  // counter-clockwise seen from outside
};

// Half the side of the square drawn for a plane, in metres.
constexpr double kPlaneDisplayHalfSize = 10.0;

// `shape` must be validated (mesh files already loaded into points/triangles).
ShapeDisplayMesh buildShapeDisplayMesh(const ShapeDesc& shape);

}  // namespace vp
