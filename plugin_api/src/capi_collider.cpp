// Rigid colliders: creation from vpColliderDef, pose/velocity access, kinematic targets.
#include <cmath>
#include <cstring>

#include "capi_convert.h"
#include "capi_copy_out.h"
#include "capi_versioned_struct.h"
#include "core/physical_limits.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

namespace {

Status translateShape(const vpShapeDef& given, ShapeDesc* out) {
  vpShapeDef in;
  VP_TRY(readVersioned("vpShapeDef", &given, vpDefaultShapeDef(), &in));
  out->type = static_cast<ShapeType>(rawEnum(in.type));
  out->radius = in.radius;
  out->halfHeight = in.halfHeight;
  out->halfExtents = toVec3(in.halfExtents);
  out->normal = toVec3(in.normal);
  out->offset = in.offset;
  out->meshScale = toVec3(in.meshScale);
  const int type = rawEnum(in.type);
  const bool usesVertices = type == vpShapeType_ConvexHull || type == vpShapeType_TriangleMesh;
  if (!usesVertices) return Status::Ok;
  if (in.points) {
    if (in.pointCount <= 0 || in.pointCount > (1 << 26))
      return fail(Status::InvalidArgument, "shape.pointCount = %d: must be in [1, 2^26] when shape.points is set",
                  in.pointCount);
    out->points.resize(static_cast<size_t>(in.pointCount));
    for (int32_t i = 0; i < in.pointCount; ++i)
      out->points[i] = Vec3(in.points[3 * i], in.points[3 * i + 1], in.points[3 * i + 2]);
  } else if (in.meshFile) {
    out->meshFile = in.meshFile;
  }
  if (type == vpShapeType_TriangleMesh && in.points) {
    if (!in.indices || in.triangleCount <= 0 || in.triangleCount > (1 << 26))
      return fail(Status::InvalidArgument,
                  "shape.indices/triangleCount = %p/%d: a triangle mesh from arrays needs indices and a count in [1, 2^26]",
                  static_cast<const void*>(in.indices), in.triangleCount);
    out->triangles.resize(static_cast<size_t>(in.triangleCount));
    std::memcpy(out->triangles.data(), in.indices, sizeof(int32_t) * 3 * static_cast<size_t>(in.triangleCount));
  }
  return Status::Ok;
}

}  // namespace

extern "C" {

vpShapeDef vpDefaultShapeDef(void) {
  vpShapeDef def{};
  def.structSize = sizeof(vpShapeDef);
  def.type = vpShapeType_Sphere;
  def.radius = 0.5f;
  def.halfHeight = 0.5f;
  def.halfExtents = vpVec3{0.5f, 0.5f, 0.5f};
  def.normal = vpVec3{0.0f, 1.0f, 0.0f};
  def.meshScale = vpVec3{1.0f, 1.0f, 1.0f};
  return def;
}

vpColliderDef vpDefaultColliderDef(void) {
  vpColliderDef def{};
  def.structSize = sizeof(vpColliderDef);
  def.bodyType = vpBodyType_Static;
  def.shape = vpDefaultShapeDef();
  def.pose.rotation.w = 1.0f;
  def.mass = 1.0f;
  def.friction = 0.5f;
  def.angularDamping = 0.05f;
  def.filter = toC(CollisionFilter{});
  return def;
}

vpStatus vpColliderCreate(vpWorldId worldId, const vpColliderDef* def, vpColliderId* outCollider) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(def);
    VP_REQUIRE_POINTER(outCollider);
    WorldLease world;
    VP_TRY(resolveWorld(worldId, &world));
    vpColliderDef d;  // the host's def, with an older header's missing fields at their defaults
    VP_TRY(readVersioned("vpColliderDef", def, vpDefaultColliderDef(), &d));
    ColliderDesc desc;
    desc.bodyType = static_cast<BodyType>(rawEnum(d.bodyType));
    VP_TRY(translateShape(d.shape, &desc.shape));
    desc.pose = toPose(d.pose);
    desc.linearVelocity = toVec3(d.linearVelocity);
    desc.angularVelocity = toVec3(d.angularVelocity);
    desc.mass = d.mass;
    desc.friction = d.friction;
    desc.restitution = d.restitution;
    desc.linearDamping = d.linearDamping;
    desc.angularDamping = d.angularDamping;
    desc.filter = toFilter(d.filter);
    desc.userData = d.userData;
    ColliderHandle h;
    VP_TRY(world->createCollider(std::move(desc), &h));
    *outCollider = makeColliderId(worldId, h);
    return Status::Ok;
  });
}

vpStatus vpColliderDestroy(vpColliderId id) {
  return guarded(__func__, [&] {
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    return w->destroyCollider(handleOf(id));
  });
}

vpStatus vpColliderIsValid(vpColliderId id) {
  return guarded(__func__, [&] {
    WorldLease w;
    Collider* c;
    return resolveCollider(id, &w, &c);
  });
}

vpStatus vpColliderGetPose(vpColliderId id, vpTransform* outPose) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outPose);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    *outPose = toC(c->pose());
    return Status::Ok;
  });
}

vpStatus vpColliderSetPose(vpColliderId id, const vpTransform* pose) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(pose);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    Pose p = toPose(*pose);
    VP_TRY(checkPose("pose", &p));
    c->setPose(p);
    return Status::Ok;
  });
}

vpStatus vpColliderGetVelocity(vpColliderId id, vpVec3* outLinear, vpVec3* outAngular) {
  return guarded(__func__, [&] {
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    if (outLinear) *outLinear = toC(c->linearVelocity());
    if (outAngular) *outAngular = toC(c->angularVelocity());
    return Status::Ok;
  });
}

vpStatus vpColliderSetVelocity(vpColliderId id, vpVec3 linear, vpVec3 angular) {
  return guarded(__func__, [&] {
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    VP_TRY(checkLinearVelocity("linear", toVec3(linear)));
    VP_TRY(checkAngularVelocity("angular", toVec3(angular)));
    if (c->bodyType() == BodyType::Static)
      return fail(Status::InvalidArgument, "collider (%u, %u) is static: it has no velocity", id.index1, id.generation);
    c->setVelocity(toVec3(linear), toVec3(angular));
    return Status::Ok;
  });
}

vpStatus vpColliderSetKinematicTarget(vpColliderId id, const vpTransform* target) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(target);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    if (c->bodyType() != BodyType::Kinematic)
      return fail(Status::InvalidArgument, "collider (%u, %u) is %s: only kinematic bodies take targets", id.index1,
                  id.generation, bodyTypeName(c->bodyType()));
    Pose p = toPose(*target);
    VP_TRY(checkPose("target", &p));
    c->setKinematicTarget(p);
    return Status::Ok;
  });
}

vpStatus vpColliderGetBodyType(vpColliderId id, vpBodyType* outType) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outType);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    *outType = static_cast<vpBodyType>(c->bodyType());
    return Status::Ok;
  });
}

vpStatus vpColliderGetUserData(vpColliderId id, void** outUserData) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outUserData);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    *outUserData = c->desc().userData;
    return Status::Ok;
  });
}

vpStatus vpWorldGetColliderCount(vpWorldId id, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    *outCount = static_cast<int32_t>(w->colliderCount());
    return Status::Ok;
  });
}

vpStatus vpWorldGetColliders(vpWorldId id, vpColliderId* outIds, int32_t capacity, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    return copyIdsOut(w->colliderHandles(), [&](ColliderHandle h) { return makeColliderId(id, h); }, outIds, capacity,
                      outCount);
  });
}

vpStatus vpWorldFindCollider(vpWorldId id, const char* name, vpColliderId* outCollider) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(name);
    VP_REQUIRE_POINTER(outCollider);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    ColliderHandle h;
    if (!w->findCollider(name, &h)) return fail(Status::InvalidArgument, "name = \"%s\": no collider has this name", name);
    *outCollider = makeColliderId(id, h);
    return Status::Ok;
  });
}

vpStatus vpColliderGetName(vpColliderId id, char* buffer, int32_t capacity, int32_t* outLength) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outLength);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    return copyStringOut(c->desc().name, buffer, capacity, outLength);
  });
}

}  // extern "C"
