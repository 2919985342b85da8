#include "query/world_query.h"

#include <btBulletCollisionCommon.h>
#include <btBulletDynamicsCommon.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/physical_limits.h"
#include "geometry/closest_point_on_triangle.h"
#include "query/triangle_queries.h"
#include "world.h"

namespace vp {
namespace {

btVector3 bt(const Vec3& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }
Vec3 toVec3(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

bool wants(const QueryFilter& filter, QueryKind kind) { return (filter.kinds & static_cast<uint32_t>(kind)) != 0; }

// Bullet filters with the same rule as CollisionFilter::meets, on the bits of the callback.
template <class Callback>
void setBulletFilter(const QueryFilter& filter, Callback* callback) {
  callback->m_collisionFilterGroup = static_cast<int>(filter.filter.category);
  callback->m_collisionFilterMask = static_cast<int>(filter.filter.mask);
}

// ---------------------------------------------------------------- colliders

// The nearest hit on each collider the ray reaches (Bullet reports every triangle of a mesh).
struct ColliderRayHits : btCollisionWorld::RayResultCallback {
  struct Hit {
    const btCollisionObject* object;
    double fraction;
    Vec3 normal;
  };
  std::vector<Hit> hits;
  bool closestOnly = false;

  btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool normalInWorldSpace) override {
    const btVector3 n = normalInWorldSpace ? r.m_hitNormalLocal
                                           : r.m_collisionObject->getWorldTransform().getBasis() * r.m_hitNormalLocal;
    auto same = std::find_if(hits.begin(), hits.end(), [&](const Hit& h) { return h.object == r.m_collisionObject; });
    if (same == hits.end())
      hits.push_back(Hit{r.m_collisionObject, r.m_hitFraction, toVec3(n)});
    else if (r.m_hitFraction < same->fraction)
      *same = Hit{r.m_collisionObject, r.m_hitFraction, toVec3(n)};
    m_collisionObject = r.m_collisionObject;
    if (closestOnly) m_closestHitFraction = std::min(m_closestHitFraction, r.m_hitFraction);
    return m_closestHitFraction;
  }
};

// Bullet's convex cast stops within about a millimetre of the surface. Where the collider has
// exact geometry, the crossing is bisected on its signed distance (whose zero set is exact for
// every shape) in a bracket around Bullet's hit, and the normal taken from its gradient.
void refineOnExactSurface(const PreparedCollider& geometry, const Ray& ray, QueryHit* hit) {
  const double bracket = 1e-2 + 1e-4 * hit->distance;
  double outside = std::max(0.0, hit->distance - bracket), inside = std::min(ray.maxDistance, hit->distance + bracket);
  auto sd = [&](double t) { return signedDistanceBound(geometry, ray.origin + t * ray.direction); };
  if (!(sd(outside) > 0.0 && sd(inside) <= 0.0)) return;  // no clean crossing: keep Bullet's
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (outside + inside);
    (sd(mid) > 0.0 ? outside : inside) = mid;
  }
  hit->distance = 0.5 * (outside + inside);
  hit->point = ray.origin + hit->distance * ray.direction;
  const double e = 1e-6 * (1.0 + hit->point.norm());
  Vec3 gradient;
  for (int k = 0; k < 3; ++k) {
    Vec3 d = Vec3::Zero();
    d[k] = e;
    gradient[k] = (signedDistanceBound(geometry, hit->point + d) - signedDistanceBound(geometry, hit->point - d)) / (2 * e);
  }
  if (gradient.norm() > 0.5) hit->normal = gradient.normalized();  // a bound's gradient may be flat
}

bool colliderHandle(World& world, const btCollisionObject* object, ColliderHandle* out) {
  return world.colliderHandleOf(static_cast<const Collider*>(object->getUserPointer()), out);
}

void raycastColliders(World& world, const Ray& ray, const QueryFilter& filter, bool closestOnly,
                      std::vector<QueryHit>* hits) {
  const Vec3 to = ray.origin + ray.maxDistance * ray.direction;
  ColliderRayHits callback;
  callback.closestOnly = closestOnly;
  // Bullet's default ray-convex test (sub-simplex) is off by millimetres on a metre sphere.
  callback.m_flags |= btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest;
  setBulletFilter(filter, &callback);
  world.collisionWorld().bullet().rayTest(bt(ray.origin), bt(to), callback);
  for (const ColliderRayHits::Hit& h : callback.hits) {
    ColliderHandle handle;
    if (!colliderHandle(world, h.object, &handle)) continue;
    QueryHit hit;
    hit.kind = QueryKind::Collider;
    hit.index1 = handle.index1;
    hit.generation = handle.generation;
    hit.distance = h.fraction * ray.maxDistance;
    hit.point = ray.origin + hit.distance * ray.direction;
    hit.normal = h.normal.normalized();
    if (const PreparedCollider* geometry = world.collider(handle)->geometry()) refineOnExactSurface(*geometry, ray, &hit);
    hits->push_back(hit);
  }
}

struct ColliderContacts : btCollisionWorld::ContactResultCallback {
  const btCollisionObject* query = nullptr;
  std::vector<const btCollisionObject*> touched;
  btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper* a, int, int,
                           const btCollisionObjectWrapper* b, int, int) override {
    const btCollisionObject* other = a->getCollisionObject() == query ? b->getCollisionObject() : a->getCollisionObject();
    // Bullet reports pairs up to its contact threshold; only touching or overlapping counts.
    if (point.getDistance() <= 0 && std::find(touched.begin(), touched.end(), other) == touched.end())
      touched.push_back(other);
    return 0;
  }
};

void overlapColliders(World& world, const OverlapShape& shape, const QueryFilter& filter,
                      std::vector<QueryHit>* hits) {
  std::unique_ptr<btConvexShape> convex;
  if (shape.type == OverlapShape::Type::Sphere)
    convex = std::make_unique<btSphereShape>(btScalar(shape.radius));
  else
    convex = std::make_unique<btBoxShape>(bt(shape.halfExtents));
  btCollisionObject object;
  object.setCollisionShape(convex.get());
  const Quat& q = shape.rotation;
  object.setWorldTransform(btTransform(btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())),
                                       bt(shape.centre)));
  ColliderContacts callback;
  callback.query = &object;
  setBulletFilter(filter, &callback);
  world.collisionWorld().bullet().contactTest(&object, callback);
  std::vector<ColliderHandle> handles;
  for (const btCollisionObject* o : callback.touched) {
    ColliderHandle h;
    if (colliderHandle(world, o, &h)) handles.push_back(h);
  }
  std::sort(handles.begin(), handles.end(), [](const ColliderHandle& a, const ColliderHandle& b) {
    return a.index1 < b.index1;
  });
  for (const ColliderHandle& h : handles) {
    QueryHit hit;
    hit.kind = QueryKind::Collider;
    hit.index1 = h.index1;
    hit.generation = h.generation;
    hits->push_back(hit);
  }
}

// ---------------------------------------------------------------- deformables

struct Aabb3 {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -Vec3::Constant(std::numeric_limits<double>::infinity());
  void add(const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
};

// The part [t0, t1] of the ray inside the box; false when it misses.
bool clipRayToBox(const Ray& ray, const Aabb3& box, double* t0, double* t1) {
  double enter = 0.0, exit = ray.maxDistance;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(ray.direction[k]) < 1e-300) {
      if (ray.origin[k] < box.lo[k] || ray.origin[k] > box.hi[k]) return false;
      continue;
    }
    double a = (box.lo[k] - ray.origin[k]) / ray.direction[k], b = (box.hi[k] - ray.origin[k]) / ray.direction[k];
    if (a > b) std::swap(a, b);
    enter = std::max(enter, a);
    exit = std::min(exit, b);
    if (enter > exit) return false;
  }
  *t0 = enter;
  *t1 = exit;
  return true;
}

// Half the size of the shape's world-axis bounding box.
Vec3 reachOf(const OverlapShape& shape, const Mat3& axes) {
  if (shape.type == OverlapShape::Type::Sphere) return Vec3::Constant(shape.radius);
  return axes.cwiseAbs() * shape.halfExtents;
}

int32_t nearestNode(const DeformableBody& body, const Vec3& point) {
  const Array<double>& x = body.positions();
  int32_t best = -1;
  double bestSq = std::numeric_limits<double>::infinity();
  for (int32_t i = 0; i < body.nodeCount(); ++i) {
    const double d = (Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - point).squaredNorm();
    if (d < bestSq) bestSq = d, best = i;
  }
  return best;
}

template <class Visit>
void forEachDeformable(World& world, const QueryFilter& filter, const Visit& visit) {
  if (!wants(filter, QueryKind::Deformable)) return;
  for (DeformableHandle h : world.deformableHandles()) {
    const DeformableBody& body = *world.deformable(h);
    if (body.desc().filter.meets(filter.filter)) visit(h, body);
  }
}

bool raycastSurface(const DeformableBody& body, const Ray& ray, QueryHit* hit) {
  const Array<Vec3>& x = body.renderPositions();
  const auto& triangles = body.renderMeshRest().triangles;
  bool found = false;
  body.renderSurfaceBvh().visitRay(ray.origin, ray.direction, ray.maxDistance, [&](int32_t t, double limit) {
    const auto& tri = triangles[static_cast<size_t>(t)];
    TriangleRayHit h;
    // Equal distances (a ray through a shared edge) keep the lower triangle id, whatever
    // order the tree visits them in.
    if (!rayHitsTriangle(ray.origin, ray.direction, limit, x[tri[0]], x[tri[1]], x[tri[2]], &h)) return limit;
    if (found && (h.distance > hit->distance || (h.distance == hit->distance && t > hit->triangle))) return limit;
    found = true;
    hit->distance = h.distance;
    hit->barycentric = h.barycentric;
    hit->triangle = t;
    return h.distance;
  });
  if (!found) return false;
  const auto& tri = triangles[static_cast<size_t>(hit->triangle)];
  hit->point = ray.origin + hit->distance * ray.direction;
  hit->normal = (x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]).normalized();
  hit->nearestNode = nearestNode(body, hit->point);
  return true;
}

// Inside the closed render surface: an odd number of crossings, by the majority of three
// skew directions (a ray through a shared edge counts both triangles and flips one parity).
bool insideSurface(const DeformableBody& body, const Vec3& point) {
  const Array<Vec3>& x = body.renderPositions();
  const auto& triangles = body.renderMeshRest().triangles;
  const Vec3 directions[3] = {Vec3(1.0, 0.3137, 0.1712).normalized(), Vec3(-0.2713, 1.0, 0.4391).normalized(),
                              Vec3(0.3571, -0.5227, 1.0).normalized()};
  int insideVotes = 0;
  for (const Vec3& d : directions) {
    int crossings = 0;
    body.renderSurfaceBvh().visitRay(point, d, std::numeric_limits<double>::infinity(), [&](int32_t t, double limit) {
      const auto& tri = triangles[static_cast<size_t>(t)];
      TriangleRayHit h;
      crossings += rayHitsTriangle(point, d, limit, x[tri[0]], x[tri[1]], x[tri[2]], &h);
      return limit;
    });
    insideVotes += crossings % 2;
  }
  return insideVotes >= 2;
}

bool surfaceOverlaps(const DeformableBody& body, const OverlapShape& shape) {
  const Array<Vec3>& x = body.renderPositions();
  const auto& triangles = body.renderMeshRest().triangles;
  const Mat3 axes = shape.rotation.toRotationMatrix();
  const Vec3 reach = reachOf(shape, axes);
  bool touches = false;
  body.renderSurfaceBvh().visitBox(shape.centre - reach, shape.centre + reach, [&](int32_t t) {
    if (touches) return;
    const auto& tri = triangles[static_cast<size_t>(t)];
    const Vec3 &a = x[tri[0]], &b = x[tri[1]], &c = x[tri[2]];
    touches = shape.type == OverlapShape::Type::Sphere
                  ? (closestPointOnTriangle(shape.centre, a, b, c) - shape.centre).norm() <= shape.radius
                  : triangleOverlapsBox(a, b, c, shape.centre, shape.halfExtents, axes);
  });
  if (touches) return true;
  // A shape wholly inside touches no triangle; one outside the surface's box is not inside.
  const RefitBvh& tree = body.renderSurfaceBvh();
  if (((shape.centre - reach) - tree.hi()).maxCoeff() > 0.0 || (tree.lo() - (shape.centre + reach)).maxCoeff() > 0.0)
    return false;
  return insideSurface(body, shape.centre);
}

template <class Handle>
QueryHit hitOn(QueryKind kind, Handle h) {
  QueryHit hit;
  hit.kind = kind;
  hit.index1 = h.index1;
  hit.generation = h.generation;
  return hit;
}

// ---------------------------------------------------------------- liquids

Aabb3 domainOf(const MacGrid& grid) {
  Aabb3 box;
  box.lo = grid.spec.origin;
  box.hi = grid.spec.origin + grid.spec.h * Vec3(grid.spec.nx, grid.spec.ny, grid.spec.nz);
  return box;
}

template <class Visit>
void forEachLiquid(World& world, const QueryFilter& filter, const Visit& visit) {
  if (!wants(filter, QueryKind::Fluid)) return;
  for (FluidHandle h : world.fluidHandles()) {
    const FluidActor& fluid = *world.fluid(h);
    if (fluid.desc().kind == FluidKind::Liquid && fluid.desc().filter.meets(filter.filter) &&
        fluid.levelSet().size() == static_cast<size_t>(fluid.grid().cellCount()))
      visit(h, fluid);
  }
}

double phiAt(const FluidActor& fluid, const Vec3& p) {
  return fluid.grid().sampleCellCentred(fluid.levelSet().data(), p);
}

Vec3 levelSetNormal(const FluidActor& fluid, const Vec3& p, const Vec3& fallback) {
  const double e = 0.5 * fluid.grid().spec.h;
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    Vec3 d = Vec3::Zero();
    d[k] = e;
    g[k] = phiAt(fluid, p + d) - phiAt(fluid, p - d);
  }
  return g.norm() > 0.0 ? Vec3(g.normalized()) : fallback;
}

// Where the ray first enters the liquid: marched at half a cell, then bisected.
bool raycastLiquid(const FluidActor& fluid, const Ray& ray, QueryHit* hit) {
  double t0, t1;
  if (!clipRayToBox(ray, domainOf(fluid.grid()), &t0, &t1)) return false;
  const double step = 0.5 * fluid.grid().spec.h;
  double outside = t0;
  if (phiAt(fluid, ray.origin + t0 * ray.direction) < 0.0) {
    hit->distance = t0;  // starts in the liquid (or enters the domain through it)
  } else {
    double inside = -1.0;
    for (double t = t0 + step;; t += step) {
      const double tc = std::min(t, t1);
      if (phiAt(fluid, ray.origin + tc * ray.direction) < 0.0) {
        inside = tc;
        break;
      }
      outside = tc;
      if (tc >= t1) break;
    }
    if (inside < 0.0) return false;
    for (int i = 0; i < 40; ++i) {  // to well below float resolution over a cell
      const double mid = 0.5 * (outside + inside);
      (phiAt(fluid, ray.origin + mid * ray.direction) < 0.0 ? inside : outside) = mid;
    }
    hit->distance = inside;
  }
  hit->point = ray.origin + hit->distance * ray.direction;
  hit->normal = levelSetNormal(fluid, hit->point, -ray.direction);
  return true;
}

// A lattice over the shape's bounding box clipped to the domain, at half a cell (coarser past
// kMaxSamplesPerAxis), keeping the points inside the shape; liquid where phi < 0.
bool liquidOverlaps(const FluidActor& fluid, const OverlapShape& shape) {
  constexpr int kMaxSamplesPerAxis = 64;
  const Mat3 axes = shape.rotation.toRotationMatrix();
  const bool sphere = shape.type == OverlapShape::Type::Sphere;
  const Aabb3 domain = domainOf(fluid.grid());
  const bool centreInDomain = (shape.centre - domain.lo).minCoeff() >= 0 && (domain.hi - shape.centre).minCoeff() >= 0;
  if (sphere && centreInDomain && phiAt(fluid, shape.centre) < shape.radius)
    return true;  // phi is a distance: the nearest liquid is within the radius
  const Vec3 reach = reachOf(shape, axes);
  const Vec3 lo = (shape.centre - reach).cwiseMax(domain.lo), hi = (shape.centre + reach).cwiseMin(domain.hi);
  if ((hi - lo).minCoeff() < 0.0) return false;
  int n[3];
  for (int k = 0; k < 3; ++k)
    n[k] = std::clamp(static_cast<int>(std::ceil((hi[k] - lo[k]) / (0.5 * fluid.grid().spec.h))), 1, kMaxSamplesPerAxis);
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) {
        const Vec3 p = lo + (hi - lo).cwiseProduct(Vec3(double(i) / n[0], double(j) / n[1], double(k) / n[2]));
        const Vec3 local = axes.transpose() * (p - shape.centre);
        const bool in = sphere ? local.norm() <= shape.radius
                               : (local.cwiseAbs() - shape.halfExtents).maxCoeff() <= 0.0;
        if (in && phiAt(fluid, p) < 0.0) return true;
      }
  return false;
}

}  // namespace

Status validateRay(const Ray& ray) {
  VP_TRY(checkPosition("ray.origin", ray.origin));
  if (!ray.direction.allFinite() || std::abs(ray.direction.norm() - 1.0) > 1e-3)
    return fail(Status::InvalidArgument, "ray.direction = (%g, %g, %g): must be a unit vector", ray.direction.x(),
                ray.direction.y(), ray.direction.z());
  if (!(ray.maxDistance >= 0.0 && ray.maxDistance <= 2.0 * std::sqrt(3.0) * kMaxCoordinate))
    return fail(Status::InvalidArgument, "ray.maxDistance = %g: must be in [0, %g] m", ray.maxDistance,
                2.0 * std::sqrt(3.0) * kMaxCoordinate);
  return Status::Ok;
}

void raycast(World& world, const Ray& ray, const QueryFilter& filter, bool closestOnly, std::vector<QueryHit>* hits) {
  hits->clear();
  if (wants(filter, QueryKind::Collider)) raycastColliders(world, ray, filter, closestOnly, hits);
  forEachDeformable(world, filter, [&](DeformableHandle h, const DeformableBody& body) {
    QueryHit hit = hitOn(QueryKind::Deformable, h);
    if (raycastSurface(body, ray, &hit)) hits->push_back(hit);
  });
  forEachLiquid(world, filter, [&](FluidHandle h, const FluidActor& fluid) {
    QueryHit hit = hitOn(QueryKind::Fluid, h);
    if (raycastLiquid(fluid, ray, &hit)) hits->push_back(hit);
  });
  std::stable_sort(hits->begin(), hits->end(),
                   [](const QueryHit& a, const QueryHit& b) { return a.distance < b.distance; });
  if (closestOnly && hits->size() > 1) hits->resize(1);
}

void overlap(World& world, const OverlapShape& shape, const QueryFilter& filter, std::vector<QueryHit>* hits) {
  hits->clear();
  if (wants(filter, QueryKind::Collider)) overlapColliders(world, shape, filter, hits);
  forEachDeformable(world, filter, [&](DeformableHandle h, const DeformableBody& body) {
    if (surfaceOverlaps(body, shape)) hits->push_back(hitOn(QueryKind::Deformable, h));
  });
  forEachLiquid(world, filter, [&](FluidHandle h, const FluidActor& fluid) {
    if (liquidOverlaps(fluid, shape)) hits->push_back(hitOn(QueryKind::Fluid, h));
  });
}

}  // namespace vp
