// Host control of rigid bodies after creation: loads, impulses, material and mass, sleeping.
#include "capi_convert.h"
#include "capi_versioned_struct.h"
#include "core/physical_limits.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

namespace {

// The dynamic body behind `id`; loads and sleep make sense for no other kind.
Status resolveDynamic(vpColliderId id, const char* what, WorldLease* w, Collider** c) {
  VP_TRY(resolveCollider(id, w, c));
  if ((*c)->bodyType() != BodyType::Dynamic)
    return fail(Status::InvalidArgument, "collider (%u, %u) is %s: only dynamic bodies %s", id.index1, id.generation,
                bodyTypeName((*c)->bodyType()), what);
  return Status::Ok;
}

// The torque about the body's origin of `load` acting at `point` (NULL: at the origin).
Status momentAbout(const Collider& c, const Vec3& load, const vpVec3* point, Vec3* torque) {
  torque->setZero();
  if (point == nullptr) return Status::Ok;
  const Vec3 p = toVec3(*point);
  VP_TRY(checkPosition("point", p));
  *torque = (p - c.pose().position).cross(load);
  return Status::Ok;
}

vpBodyProperties propertiesOf(const Collider& c) {
  const BodyProperties p = c.properties();
  vpBodyProperties out{};
  out.structSize = sizeof out;
  out.mass = c.bodyType() == BodyType::Dynamic ? static_cast<float>(p.mass) : 0.0f;
  out.friction = static_cast<float>(p.friction);
  out.restitution = static_cast<float>(p.restitution);
  out.linearDamping = static_cast<float>(p.linearDamping);
  out.angularDamping = static_cast<float>(p.angularDamping);
  return out;
}

// A force or an impulse, with the torque or angular impulse its point adds.
template <class Apply>
vpStatus applyAtPoint(const char* function, vpColliderId id, const char* field, vpVec3 value, const vpVec3* point,
                      Apply apply) {
  return guarded(function, [&] {
    WorldLease w;
    Collider* c;
    VP_TRY(resolveDynamic(id, "can be pushed", &w, &c));
    const Vec3 load = toVec3(value);
    VP_TRY(checkLoad(field, load));
    Vec3 moment;
    VP_TRY(momentAbout(*c, load, point, &moment));
    VP_TRY(checkLoad("the moment about the centre of mass", moment));
    apply(*c, load, moment);
    return Status::Ok;
  });
}

template <class Apply>
vpStatus applyRotational(const char* function, vpColliderId id, const char* field, vpVec3 value, Apply apply) {
  return guarded(function, [&] {
    WorldLease w;
    Collider* c;
    VP_TRY(resolveDynamic(id, "can be turned", &w, &c));
    const Vec3 load = toVec3(value);
    VP_TRY(checkLoad(field, load));
    apply(*c, load);
    return Status::Ok;
  });
}

}  // namespace

vpStatus vpColliderApplyForce(vpColliderId id, vpVec3 force, const vpVec3* point) {
  return applyAtPoint(__func__, id, "force", force, point,
                      [](Collider& c, const Vec3& f, const Vec3& torque) { c.addHostLoad(f, torque); });
}

vpStatus vpColliderApplyTorque(vpColliderId id, vpVec3 torque) {
  return applyRotational(__func__, id, "torque", torque,
                         [](Collider& c, const Vec3& t) { c.addHostLoad(Vec3::Zero(), t); });
}

vpStatus vpColliderApplyImpulse(vpColliderId id, vpVec3 impulse, const vpVec3* point) {
  return applyAtPoint(__func__, id, "impulse", impulse, point,
                      [](Collider& c, const Vec3& j, const Vec3& angular) { c.applyImpulse(j, angular); });
}

vpStatus vpColliderApplyAngularImpulse(vpColliderId id, vpVec3 angularImpulse) {
  return applyRotational(__func__, id, "angularImpulse", angularImpulse,
                         [](Collider& c, const Vec3& l) { c.applyImpulse(Vec3::Zero(), l); });
}

vpStatus vpColliderGetProperties(vpColliderId id, vpBodyProperties* outProperties) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outProperties);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    return writeVersioned("vpBodyProperties", propertiesOf(*c), outProperties);
  });
}

vpStatus vpColliderSetProperties(vpColliderId id, const vpBodyProperties* properties) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(properties);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    vpBodyProperties given;  // an older header's missing fields keep their current values
    VP_TRY(readVersioned("vpBodyProperties", properties, propertiesOf(*c), &given));
    BodyProperties p = c->properties();
    if (c->bodyType() == BodyType::Dynamic) p.mass = given.mass;
    p.friction = given.friction;
    p.restitution = given.restitution;
    p.linearDamping = given.linearDamping;
    p.angularDamping = given.angularDamping;
    VP_TRY(validateBodyProperties(c->bodyType(), p));
    c->setProperties(p);
    return Status::Ok;
  });
}

vpStatus vpColliderIsSleeping(vpColliderId id, int32_t* outSleeping) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outSleeping);
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    *outSleeping = c->sleeping() ? 1 : 0;
    return Status::Ok;
  });
}

vpStatus vpColliderSetSleeping(vpColliderId id, int32_t sleeping) {
  return guarded(__func__, [&] {
    WorldLease w;
    Collider* c;
    VP_TRY(resolveDynamic(id, "sleep", &w, &c));
    c->setSleeping(sleeping != 0);
    return Status::Ok;
  });
}
