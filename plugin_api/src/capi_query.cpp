// Scene queries (query/world_query.h): rays and overlaps, translated to and from the C structs.
#include <vector>

#include "capi_convert.h"
#include "core/physical_limits.h"
#include "query/world_query.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

namespace {

constexpr int32_t kMaxBatchRays = 1 << 20;

Status translateFilter(const vpQueryFilter* in, QueryFilter* out) {
  const vpQueryFilter f = in ? *in : vpDefaultQueryFilter();
  if (f.kinds < 0 || f.kinds > vpQueryKind_All)
    return fail(Status::InvalidArgument, "filter.kinds = %d: must be a combination of vpQueryKind bits (0..%d)",
                f.kinds, vpQueryKind_All);
  out->kinds = static_cast<uint32_t>(f.kinds);
  out->filter = toFilter(f.filter);
  return Status::Ok;
}

Status translateRay(const char* field, const vpRay& in, Ray* out) {
  out->origin = toVec3(in.origin);
  out->direction = toVec3(in.direction);
  out->maxDistance = in.maxDistance;
  const Status s = validateRay(*out);
  if (!ok(s)) return addErrorContext(s, field);
  out->direction.normalize();
  return Status::Ok;
}

vpQueryHit toC(vpWorldId world, const QueryHit& in) {
  vpQueryHit out{};
  switch (in.kind) {
    case QueryKind::Collider:
      out.kind = vpHitKind_Collider;
      out.collider = makeColliderId(world, ColliderHandle{in.index1, in.generation});
      break;
    case QueryKind::Deformable:
      out.kind = vpHitKind_Deformable;
      out.deformable = makeDeformableId(world, DeformableHandle{in.index1, in.generation});
      break;
    case QueryKind::Fluid:
      out.kind = vpHitKind_Liquid;
      out.fluid = makeFluidId(world, FluidHandle{in.index1, in.generation});
      break;
  }
  out.distance = static_cast<float>(in.distance);
  out.point = capi::toC(in.point);
  out.normal = capi::toC(in.normal);
  out.triangle = in.triangle;
  out.barycentric = capi::toC(in.barycentric);
  out.nearestNode = in.nearestNode;
  return out;
}

// min(capacity, hits) entries out, *outCount = all of them.
Status copyHits(vpWorldId world, const std::vector<QueryHit>& hits, vpQueryHit* outHits, int32_t capacity,
                int32_t* outCount) {
  if (capacity < 0) return fail(Status::InvalidArgument, "capacity = %d: must be >= 0", capacity);
  if (capacity > 0 && outHits == nullptr)
    return fail(Status::InvalidArgument, "outHits is NULL with capacity = %d", capacity);
  for (size_t i = 0; i < hits.size() && i < static_cast<size_t>(capacity); ++i) outHits[i] = toC(world, hits[i]);
  *outCount = static_cast<int32_t>(hits.size());
  return Status::Ok;
}

Status rayQuery(const char* function, vpWorldId worldId, const vpRay* ray, const vpQueryFilter* filter,
                bool closestOnly, vpQueryHit* outHits, int32_t capacity, int32_t* outCount) {
  if (ray == nullptr) return fail(Status::InvalidArgument, "%s: ray is NULL", function);
  if (outCount == nullptr) return fail(Status::InvalidArgument, "%s: outCount is NULL", function);
  Ray r;
  VP_TRY(translateRay("ray", *ray, &r));
  QueryFilter f;
  VP_TRY(translateFilter(filter, &f));
  WorldLease world;
  VP_TRY(resolveWorld(worldId, &world));
  std::vector<QueryHit> hits;
  raycast(*world, r, f, closestOnly, &hits);
  return copyHits(worldId, hits, outHits, capacity, outCount);
}

template <class Run>
vpStatus overlapQuery(const char* function, vpWorldId worldId, const vpQueryFilter* filter, vpQueryHit* outHits,
                      int32_t capacity, int32_t* outCount, Run makeShape) {
  return guarded(function, [&] {
    if (outCount == nullptr) return fail(Status::InvalidArgument, "%s: outCount is NULL", function);
    QueryFilter f;
    VP_TRY(translateFilter(filter, &f));
    OverlapShape shape;
    VP_TRY(makeShape(&shape));
    WorldLease world;
    VP_TRY(resolveWorld(worldId, &world));
    std::vector<QueryHit> hits;
    overlap(*world, shape, f, &hits);
    return copyHits(worldId, hits, outHits, capacity, outCount);
  });
}

}  // namespace

vpQueryFilter vpDefaultQueryFilter(void) {
  vpQueryFilter f{};
  f.kinds = vpQueryKind_All;
  f.filter = capi::toC(CollisionFilter{});
  return f;
}

vpStatus vpWorldRaycast(vpWorldId worldId, const vpRay* ray, const vpQueryFilter* filter, vpQueryHit* outHit,
                        int32_t* outHitCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outHit);
    return rayQuery(__func__, worldId, ray, filter, true, outHit, 1, outHitCount);
  });
}

vpStatus vpWorldRaycastAll(vpWorldId worldId, const vpRay* ray, const vpQueryFilter* filter, vpQueryHit* outHits,
                           int32_t capacity, int32_t* outCount) {
  return guarded(__func__, [&] { return rayQuery(__func__, worldId, ray, filter, false, outHits, capacity, outCount); });
}

vpStatus vpWorldRaycastBatch(vpWorldId worldId, const vpRay* rays, int32_t count, const vpQueryFilter* filter,
                             vpQueryHit* outHits) {
  return guarded(__func__, [&] {
    if (count < 0 || count > kMaxBatchRays)
      return fail(Status::InvalidArgument, "count = %d: must be in [0, %d]", count, kMaxBatchRays);
    if (count > 0) {
      VP_REQUIRE_POINTER(rays);
      VP_REQUIRE_POINTER(outHits);
    }
    std::vector<Ray> translated(static_cast<size_t>(count));
    for (int32_t i = 0; i < count; ++i) {
      const std::string field = "rays[" + std::to_string(i) + "]";
      VP_TRY(translateRay(field.c_str(), rays[i], &translated[static_cast<size_t>(i)]));
    }
    QueryFilter f;
    VP_TRY(translateFilter(filter, &f));
    WorldLease world;
    VP_TRY(resolveWorld(worldId, &world));
    std::vector<QueryHit> hits;
    for (int32_t i = 0; i < count; ++i) {
      raycast(*world, translated[static_cast<size_t>(i)], f, true, &hits);
      outHits[i] = hits.empty() ? vpQueryHit{} : toC(worldId, hits.front());
      if (hits.empty()) outHits[i].triangle = outHits[i].nearestNode = -1;
    }
    return Status::Ok;
  });
}

vpStatus vpWorldOverlapSphere(vpWorldId worldId, vpVec3 centre, float radius, const vpQueryFilter* filter,
                              vpQueryHit* outHits, int32_t capacity, int32_t* outCount) {
  return overlapQuery(__func__, worldId, filter, outHits, capacity, outCount, [&](OverlapShape* shape) {
    shape->type = OverlapShape::Type::Sphere;
    shape->centre = toVec3(centre);
    shape->radius = radius;
    VP_TRY(checkPosition("centre", shape->centre));
    return checkLength("radius", shape->radius);
  });
}

vpStatus vpWorldOverlapBox(vpWorldId worldId, const vpTransform* pose, vpVec3 halfExtents,
                           const vpQueryFilter* filter, vpQueryHit* outHits, int32_t capacity, int32_t* outCount) {
  return overlapQuery(__func__, worldId, filter, outHits, capacity, outCount, [&](OverlapShape* shape) {
    if (pose == nullptr) return fail(Status::InvalidArgument, "vpWorldOverlapBox: pose is NULL");
    Pose p = toPose(*pose);
    VP_TRY(checkPose("pose", &p));
    shape->type = OverlapShape::Type::Box;
    shape->centre = p.position;
    shape->rotation = p.rotation;
    shape->halfExtents = toVec3(halfExtents);
    for (int k = 0; k < 3; ++k) {
      const char* names[3] = {"halfExtents.x", "halfExtents.y", "halfExtents.z"};
      VP_TRY(checkLength(names[k], shape->halfExtents[k]));
    }
    return Status::Ok;
  });
}
