// Turns a validated ShapeDesc into a Bullet collision shape. Triangle meshes keep their
// vertex/index arrays alive in BulletShape because Bullet only references them.
#pragma once

#include <memory>
#include <vector>

#include "core/allocator.h"
#include "collide/collider_desc.h"

class btCollisionShape;
class btTriangleIndexVertexArray;

namespace vp {

struct BulletShape {
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btTriangleIndexVertexArray> meshInterface;
  Array<float> meshVertices;
  std::vector<int> meshIndices;

  BulletShape();
  ~BulletShape();
  BulletShape(BulletShape&&) noexcept;
  BulletShape& operator=(BulletShape&&) noexcept;
};

BulletShape buildBulletShape(const ShapeDesc& shape);

}  // namespace vp
