#include "collide/bullet_shape_builder.h"

#include <btBulletCollisionCommon.h>

namespace vp {

BulletShape::BulletShape() = default;
BulletShape::~BulletShape() = default;
BulletShape::BulletShape(BulletShape&&) noexcept = default;
BulletShape& BulletShape::operator=(BulletShape&&) noexcept = default;

namespace {
btVector3 bt(const Vec3& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }
}  // namespace

BulletShape buildBulletShape(const ShapeDesc& desc) {
  BulletShape out;
  switch (desc.type) {
    case ShapeType::Sphere:
      out.shape = std::make_unique<btSphereShape>(btScalar(desc.radius));
      break;
    case ShapeType::Box:
      out.shape = std::make_unique<btBoxShape>(bt(desc.halfExtents));
      break;
    case ShapeType::Capsule:
      out.shape = std::make_unique<btCapsuleShape>(btScalar(desc.radius), btScalar(2.0 * desc.halfHeight));
      break;
    case ShapeType::Cylinder:
      out.shape = std::make_unique<btCylinderShape>(btVector3(btScalar(desc.radius), btScalar(desc.halfHeight),
                                                              btScalar(desc.radius)));
      break;
    case ShapeType::Plane:
      out.shape = std::make_unique<btStaticPlaneShape>(bt(desc.normal), btScalar(desc.offset));
      break;
    case ShapeType::ConvexHull: {
      auto hull = std::make_unique<btConvexHullShape>();
      for (const Vec3& p : desc.points) hull->addPoint(bt(p), false);
      hull->recalcLocalAabb();
      out.shape = std::move(hull);
      break;
    }
    case ShapeType::TriangleMesh: {
      out.meshVertices.reserve(desc.points.size() * 3);
      for (const Vec3& p : desc.points)
        for (int k = 0; k < 3; ++k) out.meshVertices.push_back(static_cast<float>(p[k]));
      out.meshIndices.reserve(desc.triangles.size() * 3);
      for (const auto& t : desc.triangles) out.meshIndices.insert(out.meshIndices.end(), t.begin(), t.end());
      out.meshInterface = std::make_unique<btTriangleIndexVertexArray>(
          static_cast<int>(desc.triangles.size()), out.meshIndices.data(), 3 * static_cast<int>(sizeof(int)),
          static_cast<int>(desc.points.size()), out.meshVertices.data(), 3 * static_cast<int>(sizeof(float)));
      out.shape = std::make_unique<btBvhTriangleMeshShape>(out.meshInterface.get(), true);
      break;
    }
  }
  return out;
}

}  // namespace vp
