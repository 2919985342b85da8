// Scene queries, run outside a step: rays and overlaps (sphere, box) against colliders (Bullet's
// broadphase and shapes), deformables (their render surface at the current positions: what the
// host draws) and liquids (the zero level set of the last completed step). Each object is
// reported at most once: a ray's nearest hit on it. Objects are filtered by kind and by the
// collision filter rule (core/collision_filter.h) against the query's filter.
//
// Costs: colliders go through Bullet's dynamic AABB tree. A deformable is culled by the
// bounding box of its surface, then every triangle is tested (no per-deformable tree yet:
// O(triangles) per deformable the query reaches). A liquid ray marches the level set in steps
// of half a cell, then bisects; a box overlap samples the level set at half-cell spacing.
// A shape wholly inside a deformable touches none of its triangles: it counts by ray parity,
// which assumes the render surface is closed (the tet boundary is; a host's render mesh may
// not be, and then only shapes touching its triangles are found).
#pragma once

#include <cstdint>
#include <vector>

#include "core/collision_filter.h"
#include "core/math_types.h"
#include "core/status.h"

namespace vp {

class World;

enum class QueryKind : uint32_t { Collider = 1, Deformable = 2, Fluid = 4 };
constexpr uint32_t kAllQueryKinds = 7;

struct QueryFilter {
  uint32_t kinds = kAllQueryKinds;  // QueryKind bits
  CollisionFilter filter;           // an object is seen when it meets this filter
};

struct QueryHit {
  QueryKind kind = QueryKind::Collider;
  uint32_t index1 = 0, generation = 0;  // the object's handle
  double distance = 0.0;                // rays: along the ray; 0 for overlaps
  Vec3 point = Vec3::Zero(), normal = Vec3::Zero();  // rays: the hit and the surface normal
  int32_t triangle = -1;                // deformables: the render-mesh triangle hit
  Vec3 barycentric = Vec3::Zero();      // deformables: weights of its three vertices
  int32_t nearestNode = -1;             // deformables: the simulation node nearest the hit
};

struct Ray {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();  // unit length
  double maxDistance = 1e3;
};

// Messages name the fields as vpRay does: "ray.direction", "ray.maxDistance", "ray.origin".
Status validateRay(const Ray& ray);

// Every object the ray hits (its nearest hit on each), nearest first; closestOnly keeps one.
void raycast(World& world, const Ray& ray, const QueryFilter& filter, bool closestOnly, std::vector<QueryHit>* hits);

struct OverlapShape {
  enum class Type { Sphere, Box } type = Type::Sphere;
  Vec3 centre = Vec3::Zero();
  double radius = 0.5;                       // sphere
  Vec3 halfExtents = Vec3::Constant(0.5);    // box, along its rotated axes
  Quat rotation = Quat::Identity();
};

// Every object that shares a point with the shape (a collider within Bullet's contact margin
// counts), in kind order (colliders, deformables, fluids) and slot order within a kind.
void overlap(World& world, const OverlapShape& shape, const QueryFilter& filter, std::vector<QueryHit>* hits);

}  // namespace vp
