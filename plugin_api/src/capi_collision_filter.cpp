// Collision filters of colliders, deformables and fluids after creation (core/collision_filter.h
// has the rule). Every bit pattern is valid, so a call can fail only on its id or pointer.
#include "capi_convert.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

namespace {

CollisionFilter filterOf(const Collider& c) { return c.filter(); }
CollisionFilter filterOf(const DeformableBody& d) { return d.desc().filter; }
CollisionFilter filterOf(const FluidActor& f) { return f.desc().filter; }

// Bullet must hear of a collider's change; the actors read theirs at their next step.
void changeFilter(World& w, Collider& c, const CollisionFilter& filter) { w.setColliderFilter(c, filter); }
void changeFilter(World&, DeformableBody& d, const CollisionFilter& filter) { d.setCollisionFilter(filter); }
void changeFilter(World&, FluidActor& f, const CollisionFilter& filter) { f.setCollisionFilter(filter); }

template <class Id, class Object>
vpStatus getFilter(const char* function, Id id, vpCollisionFilter* outFilter,
                   Status (*resolve)(Id, WorldLease*, Object**)) {
  return guarded(function, [&] {
    if (outFilter == nullptr) return fail(Status::InvalidArgument, "%s: outFilter is NULL", function);
    WorldLease w;
    Object* object;
    VP_TRY(resolve(id, &w, &object));
    *outFilter = toC(filterOf(*object));
    return Status::Ok;
  });
}

template <class Id, class Object>
vpStatus setFilter(const char* function, Id id, vpCollisionFilter filter, Status (*resolve)(Id, WorldLease*, Object**)) {
  return guarded(function, [&] {
    WorldLease w;
    Object* object;
    VP_TRY(resolve(id, &w, &object));
    changeFilter(*w, *object, toFilter(filter));
    return Status::Ok;
  });
}

}  // namespace

vpStatus vpColliderGetCollisionFilter(vpColliderId id, vpCollisionFilter* outFilter) {
  return getFilter(__func__, id, outFilter, resolveCollider);
}
vpStatus vpColliderSetCollisionFilter(vpColliderId id, vpCollisionFilter filter) {
  return setFilter(__func__, id, filter, resolveCollider);
}
vpStatus vpDeformableGetCollisionFilter(vpDeformableId id, vpCollisionFilter* outFilter) {
  return getFilter(__func__, id, outFilter, resolveDeformable);
}
vpStatus vpDeformableSetCollisionFilter(vpDeformableId id, vpCollisionFilter filter) {
  return setFilter(__func__, id, filter, resolveDeformable);
}
vpStatus vpFluidGetCollisionFilter(vpFluidId id, vpCollisionFilter* outFilter) {
  return getFilter(__func__, id, outFilter, resolveFluid);
}
vpStatus vpFluidSetCollisionFilter(vpFluidId id, vpCollisionFilter filter) {
  return setFilter(__func__, id, filter, resolveFluid);
}
