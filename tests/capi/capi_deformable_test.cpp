// Deformable actors through the C ABI.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <vector>

#include "capi_test_support.h"

namespace {

TEST(CApiDeformable, CreateStepReadAndDestroy) {
  ScopedWorld w;
  BoxArrays box;
  vpDeformableDef def = box.def();
  def.pose.position = vpVec3{0, 5, 0};
  vpDeformableId id{};
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &id));
  int32_t nodes = 0;
  ASSERT_VP_OK(vpDeformableGetNodeCount(id, &nodes));
  EXPECT_EQ(nodes, 12);
  for (int i = 0; i < 30; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  std::vector<float> x(3 * nodes), v(3 * nodes);
  ASSERT_VP_OK(vpDeformableGetPositions(id, x.data(), nodes));
  ASSERT_VP_OK(vpDeformableGetVelocities(id, v.data(), nodes));
  // Free fall for 0.5 s: backward Euler gives v = -g t exactly for a rigidly falling body.
  for (int i = 0; i < nodes; ++i) EXPECT_NEAR(v[3 * i + 1], -9.81f * 0.5f, 1e-3f);
  EXPECT_LT(x[1], 5.0f - 1.0f);
  vpActorStats stats = vpDefaultActorStats();
  ASSERT_VP_OK(vpDeformableGetStats(id, &stats));
  EXPECT_EQ(stats.kind, vpActorKind_Deformable);
  EXPECT_GE(stats.phases[vpPhase_Solve].iterations, 0);
  EXPECT_EQ(stats.diverged, 0);
  vpStepStats step = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &step));
  EXPECT_EQ(step.actorCount, 2);  // rigid pseudo-actor + this deformable
  // Render mesh: the boundary of the box (all 12 nodes, 2 triangles per outer square).
  int32_t rv = 0, rt = 0;
  ASSERT_VP_OK(vpDeformableGetRenderMeshSize(id, &rv, &rt));
  EXPECT_EQ(rv, 12);
  EXPECT_EQ(rt, 2 * (2 + 2 + 2 + 2 + 1 + 1));
  std::vector<float> rp(3 * rv), rn(3 * rv);
  std::vector<int32_t> tris(3 * rt);
  ASSERT_VP_OK(vpDeformableGetRenderMesh(id, rp.data(), rn.data(), rv, tris.data(), rt));
  for (int i = 0; i < rv; ++i) EXPECT_NEAR(std::sqrt(rn[3 * i] * rn[3 * i] + rn[3 * i + 1] * rn[3 * i + 1] +
                                                      rn[3 * i + 2] * rn[3 * i + 2]), 1.0f, 1e-5f);
  EXPECT_EQ(vpDeformableGetRenderMesh(id, rp.data(), nullptr, rv - 1, nullptr, 0), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("vertexCapacity"));
  ASSERT_VP_OK(vpDeformableDestroy(id));
  EXPECT_EQ(vpDeformableIsValid(id), vpStatus_InvalidId);
  EXPECT_EQ(vpDeformableGetPositions(id, x.data(), nodes), vpStatus_InvalidId);
}

TEST(CApiDeformable, WorldListsItsDeformablesInSlotOrder) {
  ScopedWorld w;
  BoxArrays box;
  vpDeformableDef def = box.def();
  vpDeformableId a{}, b{}, c{};
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &a));
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &b));
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &c));
  ASSERT_VP_OK(vpDeformableDestroy(b));
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetDeformableCount(w.id, &count));
  ASSERT_EQ(count, 2);
  vpDeformableId ids[3] = {};
  ASSERT_VP_OK(vpWorldGetDeformables(w.id, ids, 3, &count));
  ASSERT_EQ(count, 2);
  EXPECT_TRUE(ids[0].index1 == a.index1 && ids[0].generation == a.generation);
  EXPECT_TRUE(ids[1].index1 == c.index1 && ids[1].generation == c.generation);
  ASSERT_VP_OK(vpWorldGetDeformables(w.id, ids, 1, &count));  // a short buffer gets a prefix
  EXPECT_EQ(count, 1);
  EXPECT_EQ(vpWorldGetDeformables(w.id, nullptr, 2, &count), vpStatus_InvalidArgument);
  EXPECT_EQ(vpWorldGetDeformableCount(vpWorldId{}, &count), vpStatus_InvalidId);
}

TEST(CApiDeformable, PinAndAttach) {
  ScopedWorld w;
  BoxArrays box;
  vpDeformableDef def = box.def();
  def.youngsModulus = 1e7f;
  vpDeformableId id;
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &id));
  // Pin the x = 0 end; attach the x = 2 end to a kinematic collider that moves up 0.1 m.
  const int32_t left[] = {0, 3, 6, 9}, right[] = {2, 5, 8, 11};
  ASSERT_VP_OK(vpDeformablePin(id, left, 4));
  vpColliderDef handle = vpDefaultColliderDef();
  handle.bodyType = vpBodyType_Kinematic;
  handle.shape.radius = 0.1f;
  handle.pose.position = vpVec3{2, 0.5f, 0.5f};
  vpColliderId handleId;
  ASSERT_VP_OK(vpColliderCreate(w.id, &handle, &handleId));
  ASSERT_VP_OK(vpDeformableAttach(id, right, 4, handleId));
  vpTransform target = {{2, 0.6f, 0.5f}, {0, 0, 0, 1}};
  ASSERT_VP_OK(vpColliderSetKinematicTarget(handleId, &target));
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  std::vector<float> x(36);
  ASSERT_VP_OK(vpDeformableGetPositions(id, x.data(), 12));
  EXPECT_FLOAT_EQ(x[0], 0.0f);
  EXPECT_FLOAT_EQ(x[1], 0.0f);
  EXPECT_NEAR(x[3 * 2 + 1], 0.1f, 1e-5f);  // node 2 rode up with the collider
  EXPECT_NEAR(x[3 * 11 + 1], 1.1f, 1e-5f);
  // Bad node lists are rejected whole.
  const int32_t bad[] = {1, 12};
  EXPECT_EQ(vpDeformablePin(id, bad, 2), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("nodes[1] = 12"));
  EXPECT_EQ(vpDeformablePin(id, nullptr, 3), vpStatus_InvalidArgument);
  // Destroying the collider releases the attachment; stepping stays fine.
  ASSERT_VP_OK(vpColliderDestroy(handleId));
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
}

TEST(CApiDeformable, AttachToAColliderOfAnotherWorldIsRejected) {
  ScopedWorld a, b;
  BoxArrays box;
  vpDeformableDef def = box.def();
  vpDeformableId id;
  ASSERT_VP_OK(vpDeformableCreate(a.id, &def, &id));
  vpColliderDef c = vpDefaultColliderDef();
  vpColliderId foreign;
  ASSERT_VP_OK(vpColliderCreate(b.id, &c, &foreign));
  const int32_t nodes[] = {0};
  EXPECT_EQ(vpDeformableAttach(id, nodes, 1, foreign), vpStatus_InvalidId);
  EXPECT_TRUE(lastErrorContains("belongs to world"));
}

TEST(CApiDeformable, DefRejectsBadValuesAndAddsNothing) {
  ScopedWorld w;
  BoxArrays box;
  struct Case {
    const char* message;
    vpStatus status;
    void (*mutate)(vpDeformableDef&);
  } cases[] = {
      {"vpDeformableDef.structSize = 6", vpStatus_VersionMismatch, [](vpDeformableDef& d) { d.structSize = 6; }},
      {"youngsModulus = 0", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.youngsModulus = 0; }},
      {"poissonRatio = 0.6", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.poissonRatio = 0.6f; }},
      {"density = -1", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.density = -1; }},
      {"density = 9.99995e-41", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.density = 1e-40f; }},
      {"pose.position = (5e+07", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.pose.position.x = 5e7f; }},
      {"solverTolerance = nan", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.solverTolerance = NAN; }},
      {"solverMaxIterations = -3", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.solverMaxIterations = -3; }},
      {"targetResidual = nan: must be finite", vpStatus_InvalidArgument,
       [](vpDeformableDef& d) { d.targetResidual = NAN; }},
      {"targetResidual = 0: must be >= solverTolerance = 0.001", vpStatus_InvalidArgument,
       [](vpDeformableDef& d) { d.targetResidual = 0.0f; }},
      {"targetResidual = 0.0005: must be >= solverTolerance = 0.001", vpStatus_InvalidArgument,
       [](vpDeformableDef& d) { d.targetResidual = 5e-4f; }},
      {"targetResidual = 0.005: must be >= solverTolerance = 0.01", vpStatus_InvalidArgument,
       [](vpDeformableDef& d) { d.solverTolerance = 0.01f, d.targetResidual = 0.005f; }},
      {"targetResidual = 1.5: must be finite and in [solverTolerance, 1]", vpStatus_InvalidArgument,
       [](vpDeformableDef& d) { d.targetResidual = 1.5f; }},
      {"priority = 1000001: must be in [-1000000, 1000000]", vpStatus_InvalidArgument,
       [](vpDeformableDef& d) { d.priority = 1000001; }},
      {"priority = -2147483648: must be in [-1000000, 1000000]", vpStatus_InvalidArgument,
       [](vpDeformableDef& d) { d.priority = INT32_MIN; }},
      {"degree = 4", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.degree = 4; }},
      {"degree = 0", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.degree = 0; }},
      {"vertexCount = 0", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.vertexCount = 0; }},
      {"tetCount = -1", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.tetCount = -1; }},
      {"both arrays", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.tets = nullptr; }},
      {"exactly one of", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.tetFile = "x.msh"; }},
      {"exactly one of", vpStatus_InvalidArgument,
       [](vpDeformableDef& d) { d.vertices = nullptr, d.tets = nullptr; }},
      {"tetFile", vpStatus_IoError,
       [](vpDeformableDef& d) { d.vertices = nullptr, d.tets = nullptr, d.tetFile = "/nope/beam.msh"; }},
      {"surfaceFile", vpStatus_IoError,
       [](vpDeformableDef& d) { d.vertices = nullptr, d.tets = nullptr, d.surfaceFile = "/nope/duck.obj"; }},
      {"pose.position", vpStatus_InvalidArgument, [](vpDeformableDef& d) { d.pose.position.x = INFINITY; }},
  };
  for (const Case& c : cases) {
    vpDeformableDef def = box.def();
    c.mutate(def);
    vpDeformableId id{};
    EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), c.status) << c.message << ": " << vpGetLastError();
    EXPECT_TRUE(lastErrorContains(c.message)) << "'" << vpGetLastError() << "' lacks '" << c.message << "'";
    EXPECT_TRUE(vpDeformableIdIsNull(id));
  }
  // A tet index out of range, an inverted-and-degenerate tet: the mesh validator names them.
  std::vector<int32_t> badTets = box.tets;
  badTets[5] = 40;
  vpDeformableDef def = box.def();
  def.tets = badTets.data();
  vpDeformableId id{};
  EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("mesh")) << vpGetLastError();
  vpStepStats stats = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldStep(w.id, 0.01f));
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &stats));
  EXPECT_EQ(stats.actorCount, 1);  // only the rigid pseudo-actor: nothing was added
}

// The accuracy floor and the priority were appended after userData: the older fields keep
// their offsets, and the defaults are the documented ones.
TEST(CApiDeformable, AccuracyFloorAndPriorityDefaultsAndBounds) {
  static_assert(offsetof(vpDeformableDef, targetResidual) > offsetof(vpDeformableDef, userData),
                "appended after the older fields");
  static_assert(offsetof(vpDeformableDef, priority) > offsetof(vpDeformableDef, targetResidual), "in header order");
  const vpDeformableDef defaults = vpDefaultDeformableDef();
  EXPECT_EQ(defaults.targetResidual, 1e-2f);
  EXPECT_EQ(defaults.priority, 0);
  EXPECT_EQ(defaults.solverTolerance, 1e-3f);
  // The bounds themselves are accepted: a floor equal to the tolerance, a floor of 1, the
  // extreme priorities.
  ScopedWorld w;
  BoxArrays box;
  const struct {
    float solverTolerance, targetResidual;
    int32_t priority;
  } accepted[] = {{1e-3f, 1e-3f, 1000000}, {1e-3f, 1.0f, -1000000}, {0.5f, 0.5f, 0}};
  for (const auto& a : accepted) {
    vpDeformableDef def = box.def();
    def.solverTolerance = a.solverTolerance;
    def.targetResidual = a.targetResidual;
    def.priority = a.priority;
    vpDeformableId id{};
    EXPECT_VP_OK(vpDeformableCreate(w.id, &def, &id)) << a.targetResidual << ", " << a.priority;
  }
  int32_t count = 0;
  ASSERT_VP_OK(vpWorldGetDeformableCount(w.id, &count));
  EXPECT_EQ(count, 3);
}

TEST(CApiDeformable, FromATetFileAndFromASurfaceFile) {
  ScopedWorld w;
  vpDeformableDef def = vpDefaultDeformableDef();
  def.tetFile = VP_TEST_DATA_DIR "/geometry/cube_v41.msh";
  vpDeformableId fromTets;
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &fromTets)) << def.tetFile;
  // A closed cube surface, voxelized at resolution 4: render mesh is the surface itself.
  const std::string obj = ::testing::TempDir() + "/vp_cube_surface.obj";
  {
    std::ofstream f(obj);
    f << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
  }
  def = vpDefaultDeformableDef();
  def.surfaceFile = obj.c_str();
  def.voxelResolution = 4;
  def.surfaceMesher = vpSurfaceMesher_Voxel;
  vpDeformableId fromSurface;
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &fromSurface));
  int32_t nodes = 0, rv = 0, rt = 0;
  ASSERT_VP_OK(vpDeformableGetNodeCount(fromSurface, &nodes));
  ASSERT_VP_OK(vpDeformableGetRenderMeshSize(fromSurface, &rv, &rt));
  EXPECT_GE(nodes, 125);  // at least the 5x5x5 lattice of the kept cells
  EXPECT_EQ(rv, 8);
  EXPECT_EQ(rt, 12);
}

// A surfaceFile must bound a solid: one quad (a sheet, parallel to the voxelizer's rays, so no
// ray parity caught it) is refused naming an open edge, and nothing is created.
TEST(CApiDeformable, AnOpenSurfaceFileIsRefusedNamingAnEdge) {
  ScopedWorld w;
  const std::string obj = ::testing::TempDir() + "/vp_open_quad.obj";
  {
    std::ofstream f(obj);
    f << "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";
  }
  vpDeformableDef def = vpDefaultDeformableDef();
  def.surfaceFile = obj.c_str();
  def.voxelResolution = 4;
  vpDeformableId id;
  EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("surfaceFile '" + obj + "': surface: is not closed: edge (")) << vpGetLastError();
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetDeformableCount(w.id, &count));
  EXPECT_EQ(count, 0);
}

}  // namespace

namespace {

// The box of BoxArrays (2 x 1 x 1, Kuhn-split cubes): dihedral angles 45-90 degrees, and its
// tets fill exactly what its boundary encloses.
TEST(CApiDeformable, MeshQualityOfABox) {
  ScopedWorld w;
  BoxArrays box;
  vpDeformableDef def = box.def();
  vpDeformableId id{};
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &id));
  float minAngle = 0, maxAngle = 0, tetVolume = 0, surfaceVolume = 0;
  ASSERT_VP_OK(vpDeformableGetMeshQuality(id, &minAngle, &maxAngle, &tetVolume, &surfaceVolume));
  EXPECT_NEAR(minAngle, 45.0f, 1e-4f);
  EXPECT_NEAR(maxAngle, 90.0f, 1e-4f);
  EXPECT_NEAR(tetVolume, 2.0f, 1e-5f);
  EXPECT_NEAR(surfaceVolume, 2.0f, 1e-5f);
  EXPECT_VP_OK(vpDeformableGetMeshQuality(id, nullptr, nullptr, nullptr, nullptr));
  EXPECT_EQ(vpDeformableGetMeshQuality(vpDeformableId{}, &minAngle, nullptr, nullptr, nullptr), vpStatus_InvalidId);
}

}  // namespace

namespace {

// A closed UV sphere of radius 0.5 (rings x segments quads, triangles at the poles) as OBJ.
std::string writeSphereObj(const std::string& name) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream f(path);
  const int rings = 24, segments = 48;
  f << "v 0 0.5 0\n";
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = M_PI * r / rings, phi = 2.0 * M_PI * s / segments;
      f << "v " << 0.5 * std::sin(theta) * std::cos(phi) << " " << 0.5 * std::cos(theta) << " "
        << -0.5 * std::sin(theta) * std::sin(phi) << "\n";
    }
  f << "v 0 -0.5 0\n";
  auto at = [&](int r, int s) { return 2 + (r - 1) * segments + (s % segments); };  // 1-based
  const int bottom = 2 + (rings - 1) * segments;
  for (int s = 0; s < segments; ++s) {
    f << "f 1 " << at(1, s) << " " << at(1, s + 1) << "\n";
    for (int r = 1; r + 1 < rings; ++r)
      f << "f " << at(r, s) << " " << at(r + 1, s) << " " << at(r + 1, s + 1) << " " << at(r, s + 1) << "\n";
    f << "f " << at(rings - 1, s) << " " << bottom << " " << at(rings - 1, s + 1) << "\n";
  }
  return path;
}

struct Quality {
  float minAngle = 0, maxAngle = 0, tetVolume = 0, surfaceVolume = 0;
};

Quality createAndMeasure(vpWorldId world, const char* file, int32_t mesher, int32_t* nodes) {
  vpDeformableDef def = vpDefaultDeformableDef();
  def.surfaceFile = file;
  def.surfaceMesher = mesher;
  vpDeformableId id{};
  Quality q;
  EXPECT_VP_OK(vpDeformableCreate(world, &def, &id));
  EXPECT_VP_OK(vpDeformableGetNodeCount(id, nodes));
  EXPECT_VP_OK(vpDeformableGetMeshQuality(id, &q.minAngle, &q.maxAngle, &q.tetVolume, &q.surfaceVolume));
  return q;
}

// The default mesher is isosurface stuffing: at the default resolution the sphere's tets keep its
// volume within 3% and their dihedral angles within the paper's bounds. The voxel mesher keeps
// every cell the surface touches, so its tets hold more than the sphere.
TEST(CApiDeformable, SurfaceFileWithEachMesher) {
  EXPECT_EQ(vpDefaultDeformableDef().surfaceMesher, vpSurfaceMesher_Default);
  ScopedWorld w;
  const std::string obj = writeSphereObj("vp_uv_sphere.obj");
  int32_t defaultNodes = 0, stuffedNodes = 0, voxelNodes = 0;
  const Quality byDefault = createAndMeasure(w.id, obj.c_str(), vpSurfaceMesher_Default, &defaultNodes);
  const Quality stuffed = createAndMeasure(w.id, obj.c_str(), vpSurfaceMesher_Stuffing, &stuffedNodes);
  const Quality voxel = createAndMeasure(w.id, obj.c_str(), vpSurfaceMesher_Voxel, &voxelNodes);
  EXPECT_EQ(defaultNodes, stuffedNodes);
  EXPECT_EQ(byDefault.tetVolume, stuffed.tetVolume);
  EXPECT_LT(std::fabs(stuffed.tetVolume - stuffed.surfaceVolume), 0.03f * stuffed.surfaceVolume);
  EXPECT_GT(stuffed.minAngle, 10.7f);
  EXPECT_LT(stuffed.maxAngle, 164.8f);
  EXPECT_GT(voxel.tetVolume, 1.2f * voxel.surfaceVolume);
  EXPECT_NEAR(voxel.minAngle, 45.0f, 1e-3f);
  EXPECT_NEAR(voxel.maxAngle, 90.0f, 1e-3f);
  EXPECT_EQ(voxel.surfaceVolume, stuffed.surfaceVolume);
}

TEST(CApiDeformable, AnUnknownSurfaceMesherIsRefusedNamingTheValue) {
  ScopedWorld w;
  const std::string obj = writeSphereObj("vp_uv_sphere_bad_mesher.obj");
  BoxArrays box;
  for (int32_t bad : {-1, 3, 1 << 30}) {
    vpDeformableDef def = vpDefaultDeformableDef();
    def.surfaceFile = obj.c_str();
    def.surfaceMesher = bad;
    vpDeformableId id{};
    EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains("surfaceMesher = " + std::to_string(bad))) << vpGetLastError();
    def = box.def();  // whatever the mesh source
    def.surfaceMesher = bad;
    EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains("surfaceMesher = " + std::to_string(bad))) << vpGetLastError();
  }
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetDeformableCount(w.id, &count));
  EXPECT_EQ(count, 0);
}

// meshGrading: 0 by default (the uniform lattice); a graded sphere at a finer lattice has fewer
// nodes than the uniform one and keeps the volume and angle bounds; out of [0, 8] it is refused
// naming the field and value, and nothing is created.
TEST(CApiDeformable, MeshGradingCoarsensTheInsideAndIsChecked) {
  EXPECT_EQ(vpDefaultDeformableDef().meshGrading, 0);
  ScopedWorld w;
  const std::string obj = writeSphereObj("vp_uv_sphere_graded.obj");
  int32_t nodes[2] = {0, 0};
  Quality q[2];
  for (int graded = 0; graded < 2; ++graded) {
    vpDeformableDef def = vpDefaultDeformableDef();
    def.surfaceFile = obj.c_str();
    def.voxelResolution = 32;
    def.meshGrading = graded ? 3 : 0;
    vpDeformableId id{};
    ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &id));
    ASSERT_VP_OK(vpDeformableGetNodeCount(id, &nodes[graded]));
    ASSERT_VP_OK(vpDeformableGetMeshQuality(id, &q[graded].minAngle, &q[graded].maxAngle, &q[graded].tetVolume,
                                            &q[graded].surfaceVolume));
    ASSERT_VP_OK(vpDeformableDestroy(id));
  }
  EXPECT_LT(nodes[1], nodes[0]);
  EXPECT_LT(std::fabs(q[1].tetVolume - q[1].surfaceVolume), 0.03f * q[1].surfaceVolume);
  EXPECT_GT(q[1].minAngle, 10.7f);
  EXPECT_LT(q[1].maxAngle, 164.8f);
  vpDeformableDef def = vpDefaultDeformableDef();
  def.surfaceFile = obj.c_str();
  vpDeformableId id{};
  for (int32_t bad : {-1, 9}) {
    def.meshGrading = bad;
    EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains("meshGrading = " + std::to_string(bad))) << vpGetLastError();
  }
  int32_t remaining = -1;
  ASSERT_VP_OK(vpWorldGetDeformableCount(w.id, &remaining));
  EXPECT_EQ(remaining, 0);
}

}  // namespace

// The surface lattice is bounded: a resolution whose tets no frame could step (and whose build
// took minutes and gigabytes) is refused naming the field, for either mesher.
TEST(CApiDeformable, ASurfaceResolutionAboveTheBoundIsRefusedNamingIt) {
  ScopedWorld w;
  const std::string obj = ::testing::TempDir() + "/vp_bound_cube.obj";
  {
    std::ofstream f(obj);
    f << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
  }
  for (int32_t mesher : {vpSurfaceMesher_Stuffing, vpSurfaceMesher_Voxel}) {
    vpDeformableDef def = vpDefaultDeformableDef();
    def.surfaceFile = obj.c_str();
    def.surfaceMesher = mesher;
    def.voxelResolution = 49;
    vpDeformableId id;
    EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains("voxelResolution = 49: must be in [1, 48]")) << vpGetLastError();
    def.voxelResolution = 0;
    EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains("voxelResolution = 0")) << vpGetLastError();
  }
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetDeformableCount(w.id, &count));
  EXPECT_EQ(count, 0);
}

TEST(CApiDeformable, ABadSelfCollisionIsRefusedNamingTheValue) {
  ScopedWorld w;
  BoxArrays box;
  EXPECT_EQ(vpDefaultDeformableDef().selfCollision, vpSelfCollision_Auto);
  for (int32_t bad : {-1, 3, 1 << 30}) {
    vpDeformableDef def = box.def();
    def.selfCollision = bad;
    vpDeformableId id{};
    EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains("selfCollision = " + std::to_string(bad))) << vpGetLastError();
  }
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetDeformableCount(w.id, &count));
  EXPECT_EQ(count, 0);
  for (int32_t good : {vpSelfCollision_Auto, vpSelfCollision_Off, vpSelfCollision_On}) {
    vpDeformableDef def = box.def();
    def.selfCollision = good;
    vpDeformableId id{};
    EXPECT_EQ(vpDeformableCreate(w.id, &def, &id), vpStatus_Ok) << vpGetLastError();
  }
}
