// Scene queries through the C ABI against analytic answers: rays on a sphere and a box
// collider, on a deformable's surface (undeformed and after it sagged), on a liquid's flat
// surface; overlaps of spheres and rotated boxes; filters; bad arguments.
#include <cmath>
#include <vector>

#include "capi_test_support.h"

namespace {

vpRay ray(vpVec3 origin, vpVec3 direction, float maxDistance = 100.0f) { return vpRay{origin, direction, maxDistance}; }

vpColliderId addStatic(vpWorldId w, vpShapeType type, vpVec3 position, vpVec3 halfExtents = {1, 1, 1}) {
  vpColliderDef def = vpDefaultColliderDef();
  def.shape.type = type;
  def.shape.radius = 1.0f;
  def.shape.halfExtents = halfExtents;
  def.pose.position = position;
  vpColliderId id{};
  EXPECT_VP_OK(vpColliderCreate(w, &def, &id));
  return id;
}

bool sameCollider(const vpColliderId& a, const vpColliderId& b) {
  return a.index1 == b.index1 && a.generation == b.generation;
}

vpQueryHit nearest(vpWorldId w, const vpRay& r, const vpQueryFilter* filter, int32_t* count) {
  vpQueryHit hit{};
  EXPECT_VP_OK(vpWorldRaycast(w, &r, filter, &hit, count));
  return hit;
}

TEST(CApiQuery, RayOnASphereAndABoxHitsWhereGeometrySays) {
  ScopedWorld w;
  const vpColliderId sphere = addStatic(w.id, vpShapeType_Sphere, vpVec3{0, 0, 0});
  const vpColliderId box = addStatic(w.id, vpShapeType_Box, vpVec3{10, 0, 0}, vpVec3{1, 2, 3});
  int32_t count = -1;
  // Sphere of radius 1 at the origin, ray along +x at height 0.5: enters at x = -sqrt(1 - 0.25).
  vpQueryHit hit = nearest(w.id, ray(vpVec3{-5, 0.5f, 0}, vpVec3{1, 0, 0}), nullptr, &count);
  ASSERT_EQ(count, 1);
  EXPECT_EQ(hit.kind, vpHitKind_Collider);
  EXPECT_TRUE(sameCollider(hit.collider, sphere));
  EXPECT_NEAR(hit.distance, 5.0f - std::sqrt(0.75f), 1e-4f);
  EXPECT_NEAR(hit.point.x, -std::sqrt(0.75f), 1e-4f);
  EXPECT_NEAR(hit.normal.x, -std::sqrt(0.75f), 1e-4f);
  EXPECT_NEAR(hit.normal.y, 0.5f, 1e-4f);
  EXPECT_EQ(hit.triangle, -1);
  EXPECT_EQ(hit.nearestNode, -1);
  // Box of half extents (1, 2, 3) at x = 10, ray down from y = 10: the top face at y = 2.
  hit = nearest(w.id, ray(vpVec3{10.5f, 10, 1}, vpVec3{0, -1, 0}), nullptr, &count);
  ASSERT_EQ(count, 1);
  EXPECT_TRUE(sameCollider(hit.collider, box));
  EXPECT_NEAR(hit.distance, 8.0f, 1e-4f);
  EXPECT_NEAR(hit.normal.y, 1.0f, 1e-4f);
  // Too short, or pointing away: no hit.
  nearest(w.id, ray(vpVec3{10.5f, 10, 1}, vpVec3{0, -1, 0}, 7.9f), nullptr, &count);
  EXPECT_EQ(count, 0);
  nearest(w.id, ray(vpVec3{-5, 0, 0}, vpVec3{-1, 0, 0}), nullptr, &count);
  EXPECT_EQ(count, 0);
}

TEST(CApiQuery, RaycastAllListsEachObjectOnceNearestFirst) {
  ScopedWorld w;
  const vpColliderId far = addStatic(w.id, vpShapeType_Sphere, vpVec3{10, 0, 0});
  const vpColliderId near = addStatic(w.id, vpShapeType_Sphere, vpVec3{4, 0, 0});
  const vpRay r = ray(vpVec3{0, 0, 0}, vpVec3{1, 0, 0});
  vpQueryHit hits[4] = {};
  int32_t count = 0;
  ASSERT_VP_OK(vpWorldRaycastAll(w.id, &r, nullptr, hits, 4, &count));
  ASSERT_EQ(count, 2);
  EXPECT_TRUE(sameCollider(hits[0].collider, near));
  EXPECT_NEAR(hits[0].distance, 3.0f, 1e-4f);
  EXPECT_TRUE(sameCollider(hits[1].collider, far));
  EXPECT_NEAR(hits[1].distance, 9.0f, 1e-4f);
  // A short buffer gets the nearest; the count says how many there are.
  vpQueryHit one{};
  ASSERT_VP_OK(vpWorldRaycastAll(w.id, &r, nullptr, &one, 1, &count));
  EXPECT_EQ(count, 2);
  EXPECT_TRUE(sameCollider(one.collider, near));
  ASSERT_VP_OK(vpWorldRaycastAll(w.id, &r, nullptr, nullptr, 0, &count));
  EXPECT_EQ(count, 2);
}

TEST(CApiQuery, FiltersLeaveOutKindsAndCategories) {
  ScopedWorld w;
  vpColliderDef def = vpDefaultColliderDef();
  def.filter = vpCollisionFilter{4, 0xFFFFFFFFu};
  vpColliderId id{};
  ASSERT_VP_OK(vpColliderCreate(w.id, &def, &id));  // a sphere of radius 0.5 at the origin
  const vpRay r = ray(vpVec3{-5, 0, 0}, vpVec3{1, 0, 0});
  int32_t count = 0;
  nearest(w.id, r, nullptr, &count);
  EXPECT_EQ(count, 1);
  vpQueryFilter onlyDeformables = vpDefaultQueryFilter();
  onlyDeformables.kinds = vpQueryKind_Deformables | vpQueryKind_Liquids;
  nearest(w.id, r, &onlyDeformables, &count);
  EXPECT_EQ(count, 0);
  vpQueryFilter notCategory4 = vpDefaultQueryFilter();
  notCategory4.filter.maskBits = ~4u;
  nearest(w.id, r, &notCategory4, &count);
  EXPECT_EQ(count, 0);
  vpQueryHit hits[2];
  ASSERT_VP_OK(vpWorldOverlapSphere(w.id, vpVec3{0, 0, 0}, 0.1f, &notCategory4, hits, 2, &count));
  EXPECT_EQ(count, 0);
}

// A 2 x 1 x 1 m box of 12 tets with its low corner at `corner`.
struct BoxDeformable {
  BoxArrays box;
  vpDeformableId id{};
  BoxDeformable(vpWorldId w, vpVec3 corner, float youngsModulus = 1e6f) {
    vpDeformableDef def = box.def();
    def.pose.position = corner;
    def.youngsModulus = youngsModulus;
    EXPECT_VP_OK(vpDeformableCreate(w, &def, &id));
  }
};

TEST(CApiQuery, RayOnADeformableHitsItsSurfaceAsDrawnBeforeAndAfterItSags) {
  ScopedWorld w;
  BoxDeformable jelly(w.id, vpVec3{0, 1, 0}, 2e4f);
  const int32_t pinned[4] = {0, 3, 6, 9};  // the x = 0 end
  ASSERT_VP_OK(vpDeformablePin(jelly.id, pinned, 4));
  const vpRay down = ray(vpVec3{1.7f, 5, 0.3f}, vpVec3{0, -1, 0});
  for (int pass = 0; pass < 2; ++pass) {
    SCOPED_TRACE(pass);
    int32_t count = 0;
    const vpQueryHit hit = nearest(w.id, down, nullptr, &count);
    ASSERT_EQ(count, 1);
    EXPECT_EQ(hit.kind, vpHitKind_Deformable);
    EXPECT_EQ(hit.deformable.index1, jelly.id.index1);
    if (pass == 0) {
      EXPECT_NEAR(hit.distance, 3.0f, 1e-5f);  // the top face, y = 2
    }
    EXPECT_NEAR(hit.barycentric.x + hit.barycentric.y + hit.barycentric.z, 1.0f, 1e-5f);
    // The hit lies on the drawn triangle at the current positions.
    int32_t nv = 0, nt = 0;
    ASSERT_VP_OK(vpDeformableGetRenderMeshSize(jelly.id, &nv, &nt));
    std::vector<float> positions(3 * nv), normals(3 * nv);
    std::vector<int32_t> triangles(3 * nt);
    ASSERT_VP_OK(vpDeformableGetRenderMesh(jelly.id, positions.data(), normals.data(), nv, triangles.data(), nt));
    ASSERT_GE(hit.triangle, 0);
    ASSERT_LT(hit.triangle, nt);
    const float weights[3] = {hit.barycentric.x, hit.barycentric.y, hit.barycentric.z};
    float on[3] = {0, 0, 0};
    for (int corner = 0; corner < 3; ++corner)
      for (int k = 0; k < 3; ++k) on[k] += weights[corner] * positions[3 * triangles[3 * hit.triangle + corner] + k];
    EXPECT_NEAR(on[0], hit.point.x, 1e-4f);
    EXPECT_NEAR(on[1], hit.point.y, 1e-4f);
    EXPECT_NEAR(on[2], hit.point.z, 1e-4f);
    EXPECT_GT(hit.normal.y, 0.9f);  // the top, facing up
    // The nearest node, by brute force over the current node positions.
    std::vector<float> x(3 * 12);
    ASSERT_VP_OK(vpDeformableGetPositions(jelly.id, x.data(), 12));
    int32_t best = -1;
    float bestSq = 1e30f;
    for (int32_t i = 0; i < 12; ++i) {
      const float dx = x[3 * i] - hit.point.x, dy = x[3 * i + 1] - hit.point.y, dz = x[3 * i + 2] - hit.point.z;
      if (dx * dx + dy * dy + dz * dz < bestSq) bestSq = dx * dx + dy * dy + dz * dz, best = i;
    }
    EXPECT_EQ(hit.nearestNode, best);
    if (pass == 0) {
      for (int i = 0; i < 30; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));  // the free end sags
    }
  }
  int32_t count = 0;
  const vpQueryHit after = nearest(w.id, down, nullptr, &count);
  EXPECT_GT(after.distance, 3.0f + 1e-3f);  // the surface under the ray went down
}

// A liquid tank 1 x 1 x 1 m of 16^3 cells, filled to `level`.
vpFluidId addTank(vpWorldId w, float level) {
  vpFluidDef def = vpDefaultFluidDef();
  def.kind = vpFluidKind_Liquid;
  def.resolution[0] = def.resolution[1] = def.resolution[2] = 16;
  def.cellSize = 1.0f / 16.0f;
  vpFluidRegion water{};
  water.type = vpRegionType_Box;
  water.centre = vpVec3{0.5f, 0.5f * level, 0.5f};
  water.halfExtents = vpVec3{1.0f, 0.5f * level, 1.0f};
  def.initialLiquid = &water;
  def.initialLiquidCount = 1;
  vpFluidId id{};
  EXPECT_VP_OK(vpFluidCreate(w, &def, &id));
  return id;
}

TEST(CApiQuery, RayOnALiquidFindsItsFlatSurface) {
  vpWorldDef def = unbudgetedWorldDef();
  def.gravity = vpVec3{0, 0, 0};  // the surface stays where it was put
  ScopedWorld w(def);
  const vpFluidId tank = addTank(w.id, 0.4f);
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  int32_t count = 0;
  vpQueryHit hit = nearest(w.id, ray(vpVec3{0.5f, 2, 0.5f}, vpVec3{0, -1, 0}), nullptr, &count);
  ASSERT_EQ(count, 1);
  EXPECT_EQ(hit.kind, vpHitKind_Liquid);
  EXPECT_EQ(hit.fluid.index1, tank.index1);
  // The level set of a flat surface is linear in y, which trilinear sampling reproduces.
  EXPECT_NEAR(hit.point.y, 0.4f, 2e-3f);
  EXPECT_NEAR(hit.normal.y, 1.0f, 1e-3f);
  // A slanted ray meets the same plane.
  const float s = std::sqrt(0.5f);
  hit = nearest(w.id, ray(vpVec3{0.2f, 0.9f, 0.5f}, vpVec3{s, -s, 0}), nullptr, &count);
  ASSERT_EQ(count, 1);
  EXPECT_NEAR(hit.distance, 0.5f / s, 3e-3f);
  // From inside the liquid: a hit at distance 0.
  hit = nearest(w.id, ray(vpVec3{0.5f, 0.2f, 0.5f}, vpVec3{1, 0, 0}), nullptr, &count);
  ASSERT_EQ(count, 1);
  EXPECT_EQ(hit.distance, 0.0f);
  // Above the surface, horizontally: nothing.
  nearest(w.id, ray(vpVec3{-1, 0.6f, 0.5f}, vpVec3{1, 0, 0}), nullptr, &count);
  EXPECT_EQ(count, 0);
}

TEST(CApiQuery, OverlapsFindCollidersDeformablesAndLiquids) {
  vpWorldDef def = unbudgetedWorldDef();
  def.gravity = vpVec3{0, 0, 0};
  ScopedWorld w(def);
  const vpColliderId box = addStatic(w.id, vpShapeType_Box, vpVec3{-3, 0, 0});  // half extents 1
  BoxDeformable jelly(w.id, vpVec3{3, 0, 0});
  addTank(w.id, 0.4f);
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  vpQueryHit hits[4];
  int32_t count = 0;
  ASSERT_VP_OK(vpWorldOverlapSphere(w.id, vpVec3{-1.5f, 0, 0}, 0.6f, nullptr, hits, 4, &count));
  ASSERT_EQ(count, 1);  // reaches x = -2.1 < -2: into the box
  EXPECT_TRUE(sameCollider(hits[0].collider, box));
  ASSERT_VP_OK(vpWorldOverlapSphere(w.id, vpVec3{-1.5f, 0, 0}, 0.4f, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 0);
  // A box of half extents 0.5 at x = -1.4 reaches -1.9 (clear of the box); turned 45 degrees
  // about z its corner reaches -1.4 - 0.707 = -2.11 (into it).
  vpTransform pose{vpVec3{-1.4f, 0, 0}, vpQuat{0, 0, 0, 1}};
  ASSERT_VP_OK(vpWorldOverlapBox(w.id, &pose, vpVec3{0.5f, 0.5f, 0.5f}, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 0);
  pose.rotation = vpQuat{0, 0, std::sin(0.3926991f), std::cos(0.3926991f)};
  ASSERT_VP_OK(vpWorldOverlapBox(w.id, &pose, vpVec3{0.5f, 0.5f, 0.5f}, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 1);
  // The deformable spans x in [3, 5], y and z in [0, 1]: touching its face, and wholly inside.
  ASSERT_VP_OK(vpWorldOverlapSphere(w.id, vpVec3{2.7f, 0.5f, 0.5f}, 0.35f, nullptr, hits, 4, &count));
  ASSERT_EQ(count, 1);
  EXPECT_EQ(hits[0].kind, vpHitKind_Deformable);
  ASSERT_VP_OK(vpWorldOverlapSphere(w.id, vpVec3{2.7f, 0.5f, 0.5f}, 0.25f, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 0);
  ASSERT_VP_OK(vpWorldOverlapSphere(w.id, vpVec3{4.0f, 0.5f, 0.5f}, 0.1f, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 1);
  pose = vpTransform{vpVec3{4.0f, 0.5f, 0.5f}, vpQuat{0, 0, 0, 1}};
  ASSERT_VP_OK(vpWorldOverlapBox(w.id, &pose, vpVec3{0.1f, 0.1f, 0.1f}, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 1);
  // The liquid fills y < 0.4 of the unit cube at the origin.
  ASSERT_VP_OK(vpWorldOverlapSphere(w.id, vpVec3{0.5f, 0.55f, 0.5f}, 0.2f, nullptr, hits, 4, &count));
  ASSERT_EQ(count, 1);
  EXPECT_EQ(hits[0].kind, vpHitKind_Liquid);
  ASSERT_VP_OK(vpWorldOverlapSphere(w.id, vpVec3{0.5f, 0.55f, 0.5f}, 0.1f, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 0);
  pose = vpTransform{vpVec3{0.5f, 0.6f, 0.5f}, vpQuat{0, 0, 0, 1}};
  ASSERT_VP_OK(vpWorldOverlapBox(w.id, &pose, vpVec3{0.3f, 0.25f, 0.3f}, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 1);
  ASSERT_VP_OK(vpWorldOverlapBox(w.id, &pose, vpVec3{0.3f, 0.15f, 0.3f}, nullptr, hits, 4, &count));
  EXPECT_EQ(count, 0);
}

TEST(CApiQuery, BatchGivesEachRayItsNearestHitOrNone) {
  ScopedWorld w;
  addStatic(w.id, vpShapeType_Sphere, vpVec3{0, 0, 0});
  const vpRay rays[3] = {ray(vpVec3{-5, 0, 0}, vpVec3{1, 0, 0}), ray(vpVec3{-5, 3, 0}, vpVec3{1, 0, 0}),
                         ray(vpVec3{0, 5, 0}, vpVec3{0, -1, 0})};
  vpQueryHit hits[3];
  ASSERT_VP_OK(vpWorldRaycastBatch(w.id, rays, 3, nullptr, hits));
  EXPECT_EQ(hits[0].kind, vpHitKind_Collider);
  EXPECT_NEAR(hits[0].distance, 4.0f, 1e-4f);
  EXPECT_EQ(hits[1].kind, vpHitKind_None);
  EXPECT_EQ(hits[2].kind, vpHitKind_Collider);
  EXPECT_NEAR(hits[2].distance, 4.0f, 1e-4f);
  ASSERT_VP_OK(vpWorldRaycastBatch(w.id, nullptr, 0, nullptr, nullptr));
}

TEST(CApiQuery, BadArgumentsAreNamed) {
  ScopedWorld w;
  vpQueryHit hit{};
  int32_t count = 7;
  struct Case {
    vpRay r;
    const char* message;
  } cases[] = {
      {ray(vpVec3{0, 0, 0}, vpVec3{0, 0, 0}), "ray: ray.direction = (0, 0, 0): must be a unit vector"},
      {ray(vpVec3{0, 0, 0}, vpVec3{2, 0, 0}), "ray.direction = (2, 0, 0)"},
      {ray(vpVec3{NAN, 0, 0}, vpVec3{1, 0, 0}), "ray.origin = (nan"},
      {ray(vpVec3{0, 0, 0}, vpVec3{1, 0, 0}, -1.0f), "ray.maxDistance = -1"},
      {ray(vpVec3{0, 0, 0}, vpVec3{1, 0, 0}, INFINITY), "ray.maxDistance = inf"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(vpWorldRaycast(w.id, &c.r, nullptr, &hit, &count), vpStatus_InvalidArgument) << c.message;
    EXPECT_TRUE(lastErrorContains(c.message)) << vpGetLastError();
  }
  EXPECT_EQ(count, 7);  // nothing written
  const vpRay good = ray(vpVec3{0, 0, 0}, vpVec3{1, 0, 0});
  vpQueryFilter filter = vpDefaultQueryFilter();
  filter.kinds = 9;
  EXPECT_EQ(vpWorldRaycast(w.id, &good, &filter, &hit, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("filter.kinds = 9")) << vpGetLastError();
  EXPECT_EQ(vpWorldRaycast(w.id, nullptr, nullptr, &hit, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("ray is NULL")) << vpGetLastError();
  EXPECT_EQ(vpWorldRaycastAll(w.id, &good, nullptr, nullptr, 3, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("outHits is NULL with capacity = 3")) << vpGetLastError();
  EXPECT_EQ(vpWorldRaycastAll(w.id, &good, nullptr, &hit, -1, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("capacity = -1")) << vpGetLastError();
  EXPECT_EQ(vpWorldRaycastBatch(w.id, &good, -2, nullptr, &hit), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("count = -2")) << vpGetLastError();
  const vpRay batch[2] = {good, ray(vpVec3{0, 0, 0}, vpVec3{0, 0, 0})};
  vpQueryHit two[2];
  EXPECT_EQ(vpWorldRaycastBatch(w.id, batch, 2, nullptr, two), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("rays[1]: ray.direction")) << vpGetLastError();
  EXPECT_EQ(vpWorldOverlapSphere(w.id, vpVec3{0, 0, 0}, 0.0f, nullptr, &hit, 1, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("radius = 0")) << vpGetLastError();
  vpTransform pose{vpVec3{0, 0, 0}, vpQuat{0, 0, 0, 0}};
  EXPECT_EQ(vpWorldOverlapBox(w.id, &pose, vpVec3{1, 1, 1}, nullptr, &hit, 1, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("pose.rotation")) << vpGetLastError();
  pose.rotation.w = 1;
  EXPECT_EQ(vpWorldOverlapBox(w.id, &pose, vpVec3{1, -1, 1}, nullptr, &hit, 1, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("halfExtents.y = -1")) << vpGetLastError();
  EXPECT_EQ(vpWorldOverlapBox(w.id, nullptr, vpVec3{1, 1, 1}, nullptr, &hit, 1, &count), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("pose is NULL")) << vpGetLastError();
  const vpWorldId stale = w.id;
  ASSERT_VP_OK(vpWorldDestroy(w.id));
  EXPECT_EQ(vpWorldRaycast(stale, &good, nullptr, &hit, &count), vpStatus_InvalidId);
}

}  // namespace
