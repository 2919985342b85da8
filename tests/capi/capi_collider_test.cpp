// Collider defs: every field validated with a message naming it; failures change nothing.
#include <cmath>
#include <fstream>

#include "capi_test_support.h"

namespace {

int32_t colliderCount(vpWorldId w) {
  int32_t n = -1;
  vpWorldGetColliderCount(w, &n);
  return n;
}

TEST(CApiCollider, DefRejectsBadValuesAndAddsNothing) {
  ScopedWorld w;
  struct Case {
    const char* message;
    vpStatus status;
    void (*mutate)(vpColliderDef&);
  } cases[] = {
      {"vpColliderDef.structSize", vpStatus_VersionMismatch, [](vpColliderDef& d) { d.structSize = 0; }},
      {"vpShapeDef.structSize", vpStatus_VersionMismatch, [](vpColliderDef& d) { d.shape.structSize = 1; }},
      {"bodyType = 9", vpStatus_InvalidArgument, [](vpColliderDef& d) { setRawEnum(d.bodyType, 9); }},
      {"shape.type = 42", vpStatus_InvalidArgument, [](vpColliderDef& d) { setRawEnum(d.shape.type, 42); }},
      {"shape.radius = -1", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.shape.radius = -1; }},
      {"shape.radius = nan", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.shape.radius = NAN; }},
      {"shape.radius = inf", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.shape.radius = INFINITY; }},
      {"shape.halfExtents.z = 0", vpStatus_InvalidArgument,
       [](vpColliderDef& d) { d.shape.type = vpShapeType_Box; d.shape.halfExtents.z = 0; }},
      {"shape.halfHeight = -3", vpStatus_InvalidArgument,
       [](vpColliderDef& d) { d.shape.type = vpShapeType_Capsule; d.shape.halfHeight = -3; }},
      {"shape.normal", vpStatus_InvalidArgument,
       [](vpColliderDef& d) { d.shape.type = vpShapeType_Plane; d.shape.normal = vpVec3{0, 0, 0}; }},
      {"pose.position", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.pose.position.z = NAN; }},
      {"pose.rotation", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.pose.rotation = vpQuat{0, 0, 0, 0}; }},
      {"mass = -1", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.bodyType = vpBodyType_Dynamic; d.mass = -1; }},
      // Below the physical minimum (core/physical_limits.h): a denormal mass turned a dynamic
      // sphere's pose into NaN within a few steps; a micro-size shape; a position or speed a
      // float cannot hold usefully (a JSON 1e308 would become +inf).
      {"mass = 9.99995e-41", vpStatus_InvalidArgument,  // 1e-40f, a denormal float
       [](vpColliderDef& d) { d.bodyType = vpBodyType_Dynamic; d.mass = 1e-40f; }},
      {"shape.radius = 1e-09", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.shape.radius = 1e-9f; }},
      {"pose.position = (1e+30", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.pose.position.x = 1e30f; }},
      {"pose.position = (0, -2e+06", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.pose.position.y = -2e6f; }},
      {"linearVelocity = (0, 0, 1e+30)", vpStatus_InvalidArgument,
       [](vpColliderDef& d) { d.bodyType = vpBodyType_Dynamic; d.linearVelocity.z = 1e30f; }},
      {"angularVelocity = (1e+06", vpStatus_InvalidArgument,
       [](vpColliderDef& d) { d.bodyType = vpBodyType_Dynamic; d.angularVelocity.x = 1e6f; }},
      {"friction = nan", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.friction = NAN; }},
      {"restitution = 2", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.restitution = 2; }},
      {"linearDamping = -0.5", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.linearDamping = -0.5f; }},
      {"angularDamping = 3", vpStatus_InvalidArgument, [](vpColliderDef& d) { d.angularDamping = 3; }},
      {"shape.pointCount = 0", vpStatus_InvalidArgument, [](vpColliderDef& d) {
         static const float pts[3] = {0, 0, 0};
         d.shape.type = vpShapeType_ConvexHull;
         d.shape.points = pts;
         d.shape.pointCount = 0;
       }},
      {"shape.points = NULL", vpStatus_InvalidArgument,
       [](vpColliderDef& d) { d.shape.type = vpShapeType_ConvexHull; }},
      {"shape.indices/triangleCount", vpStatus_InvalidArgument, [](vpColliderDef& d) {
         static const float pts[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
         d.shape.type = vpShapeType_TriangleMesh;
         d.shape.points = pts;
         d.shape.pointCount = 3;
       }},
      {"shape.indices[1] = -4", vpStatus_InvalidArgument, [](vpColliderDef& d) {
         static const float pts[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
         static const int32_t idx[3] = {0, -4, 2};
         d.shape.type = vpShapeType_TriangleMesh;
         d.shape.points = pts;
         d.shape.pointCount = 3;
         d.shape.indices = idx;
         d.shape.triangleCount = 1;
       }},
      {"shape.points[1] = (nan", vpStatus_InvalidArgument, [](vpColliderDef& d) {
         static const float pts[12] = {0, 0, 0, NAN, 0, 0, 0, 1, 0, 0, 0, 1};
         d.shape.type = vpShapeType_ConvexHull;
         d.shape.points = pts;
         d.shape.pointCount = 4;
       }},
      {"use a convex hull", vpStatus_Unsupported, [](vpColliderDef& d) {
         static const float pts[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
         static const int32_t idx[3] = {0, 1, 2};
         d.bodyType = vpBodyType_Dynamic;
         d.shape.type = vpShapeType_TriangleMesh;
         d.shape.points = pts;
         d.shape.pointCount = 3;
         d.shape.indices = idx;
         d.shape.triangleCount = 1;
       }},
      {"shape.meshFile: file '/no/such/file.obj': cannot be opened", vpStatus_IoError,
       [](vpColliderDef& d) { d.shape.type = vpShapeType_TriangleMesh; d.shape.meshFile = "/no/such/file.obj"; }},
  };
  for (const Case& c : cases) {
    vpColliderDef def = vpDefaultColliderDef();
    c.mutate(def);
    vpColliderId id{};
    EXPECT_EQ(vpColliderCreate(w.id, &def, &id), c.status) << c.message << ": " << vpGetLastError();
    EXPECT_TRUE(lastErrorContains(c.message)) << "'" << vpGetLastError() << "' lacks '" << c.message << "'";
    EXPECT_TRUE(vpColliderIdIsNull(id));
  }
  EXPECT_EQ(colliderCount(w.id), 0);
  vpColliderDef ok = vpDefaultColliderDef();
  EXPECT_EQ(vpColliderCreate(w.id, &ok, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("outCollider is NULL"));
}

TEST(CApiCollider, MalformedMeshFileIsAParseError) {
  ScopedWorld w;
  const std::string path = ::testing::TempDir() + "/garbage.obj";
  std::ofstream(path) << "this is not a mesh\n";
  vpColliderDef def = vpDefaultColliderDef();
  def.shape.type = vpShapeType_TriangleMesh;
  def.shape.meshFile = path.c_str();
  vpColliderId id;
  vpStatus s = vpColliderCreate(w.id, &def, &id);
  EXPECT_EQ(s, vpStatus_ParseError) << vpGetLastError();
  EXPECT_TRUE(lastErrorContains("garbage.obj"));
  EXPECT_EQ(colliderCount(w.id), 0);
}

TEST(CApiCollider, ConvexHullAndMeshFromArrays) {
  ScopedWorld w;
  const float floorPts[12] = {-5, 0, -5, 5, 0, -5, -5, 0, 5, 5, 0, 5};
  const int32_t floorIdx[6] = {0, 2, 1, 1, 2, 3};
  vpColliderDef floor = vpDefaultColliderDef();
  floor.shape.type = vpShapeType_TriangleMesh;
  floor.shape.points = floorPts;
  floor.shape.pointCount = 4;
  floor.shape.indices = floorIdx;
  floor.shape.triangleCount = 2;
  vpColliderId floorId, gemId;
  ASSERT_VP_OK(vpColliderCreate(w.id, &floor, &floorId));
  // A unit cube as a hull of its 8 corners: rests at half height 0.5 * scale.
  float cube[24];
  for (int i = 0; i < 8; ++i) {
    cube[3 * i] = (i & 1) ? 0.5f : -0.5f;
    cube[3 * i + 1] = (i & 2) ? 0.5f : -0.5f;
    cube[3 * i + 2] = (i & 4) ? 0.5f : -0.5f;
  }
  vpColliderDef gem = vpDefaultColliderDef();
  gem.bodyType = vpBodyType_Dynamic;
  gem.shape.type = vpShapeType_ConvexHull;
  gem.shape.points = cube;
  gem.shape.pointCount = 8;
  gem.shape.meshScale = vpVec3{1, 0.4f, 1};
  gem.pose.position.y = 1;
  ASSERT_VP_OK(vpColliderCreate(w.id, &gem, &gemId));
  for (int i = 0; i < 180; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  vpTransform pose;
  ASSERT_VP_OK(vpColliderGetPose(gemId, &pose));
  // Convex hulls carry Bullet's 0.04 m margin outside the points: rest height 0.2 + margin.
  EXPECT_NEAR(pose.position.y, 0.2f + 0.04f, 0.01f);
}

TEST(CApiCollider, PoseVelocityAndKinematicTarget) {
  ScopedWorld w;
  vpColliderDef kin = vpDefaultColliderDef();
  kin.bodyType = vpBodyType_Kinematic;
  kin.shape.type = vpShapeType_Box;
  vpColliderId id;
  ASSERT_VP_OK(vpColliderCreate(w.id, &kin, &id));
  vpTransform target = {{1, 2, 3}, {0, 0, 0, 1}};
  ASSERT_VP_OK(vpColliderSetKinematicTarget(id, &target));
  ASSERT_VP_OK(vpWorldStep(w.id, 0.5f));
  vpTransform pose;
  vpVec3 lin, ang;
  ASSERT_VP_OK(vpColliderGetPose(id, &pose));
  ASSERT_VP_OK(vpColliderGetVelocity(id, &lin, &ang));
  EXPECT_FLOAT_EQ(pose.position.z, 3.0f);
  EXPECT_FLOAT_EQ(lin.x, 2.0f);  // 1 m in 0.5 s
  vpTransform bad = {{0, 0, 0}, {0, 0, 0, 5}};
  EXPECT_EQ(vpColliderSetKinematicTarget(id, &bad), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("target.rotation"));
  // Targets are for kinematic bodies only; static bodies have no velocity.
  vpColliderDef stat = vpDefaultColliderDef();
  vpColliderId sid;
  ASSERT_VP_OK(vpColliderCreate(w.id, &stat, &sid));
  EXPECT_EQ(vpColliderSetKinematicTarget(sid, &target), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("only kinematic"));
  EXPECT_EQ(vpColliderSetVelocity(sid, lin, ang), vpStatus_InvalidArgument);
  // Teleport works for any body type and is validated.
  ASSERT_VP_OK(vpColliderSetPose(sid, &target));
  ASSERT_VP_OK(vpColliderGetPose(sid, &pose));
  EXPECT_FLOAT_EQ(pose.position.y, 2.0f);
  vpTransform nanPose = {{NAN, 0, 0}, {0, 0, 0, 1}};
  EXPECT_EQ(vpColliderSetPose(sid, &nanPose), vpStatus_InvalidArgument);
  vpTransform farPose = {{0, 0, 3e6f}, {0, 0, 0, 1}};
  EXPECT_EQ(vpColliderSetPose(sid, &farPose), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("pose.position = (0, 0, 3e+06): coordinates must be finite and within"));
  EXPECT_EQ(vpColliderSetKinematicTarget(id, &farPose), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("target.position"));
  ASSERT_VP_OK(vpColliderGetPose(sid, &pose));
  EXPECT_FLOAT_EQ(pose.position.x, 1.0f);
  EXPECT_FLOAT_EQ(pose.position.z, 3.0f);
}

TEST(CApiCollider, DynamicVelocityAndUserData) {
  ScopedWorld w;
  int tag = 5;
  vpColliderDef def = dynamicBall(10.0f);
  def.userData = &tag;
  vpColliderId id;
  ASSERT_VP_OK(vpColliderCreate(w.id, &def, &id));
  void* user = nullptr;
  ASSERT_VP_OK(vpColliderGetUserData(id, &user));
  EXPECT_EQ(user, &tag);
  ASSERT_VP_OK(vpWorldSetGravity(w.id, vpVec3{0, 0, 0}));
  ASSERT_VP_OK(vpColliderSetVelocity(id, vpVec3{3, 0, 0}, vpVec3{0, 0, 0}));
  ASSERT_VP_OK(vpWorldStep(w.id, 0.5f));
  vpTransform pose;
  ASSERT_VP_OK(vpColliderGetPose(id, &pose));
  EXPECT_NEAR(pose.position.x, 1.5f, 1e-4f);
  EXPECT_EQ(vpColliderSetVelocity(id, vpVec3{INFINITY, 0, 0}, vpVec3{0, 0, 0}), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("linear"));
  EXPECT_EQ(vpColliderSetVelocity(id, vpVec3{0, 0, 0}, vpVec3{0, 2e5f, 0}), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("angular = (0, 200000, 0): must be finite with magnitude <= 100000 rad/s"));
  vpVec3 lin, ang;
  ASSERT_VP_OK(vpColliderGetVelocity(id, &lin, &ang));
  EXPECT_FLOAT_EQ(lin.x, 3.0f);
  EXPECT_FLOAT_EQ(ang.y, 0.0f);
}

}  // namespace
