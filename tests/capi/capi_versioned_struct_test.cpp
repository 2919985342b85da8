// The struct-size policy (volphys.h, "Versioned structs"): a struct from an older header is a
// prefix of this one. Each test hands the library a struct cut at every field, in a heap block
// of exactly structSize bytes, so that a read past it is caught by AddressSanitizer (the asan
// preset runs these tests); the fields past the cut must take their defaults, and stats are
// written up to the cut only. The field lists here are written independently of the library's.
#include <cstddef>
#include <cstring>
#include <memory>
#include <vector>

#include "capi_test_support.h"

namespace {

// `full` cut to its first `size` bytes, in a block of exactly that size, structSize = size.
template <class T>
std::unique_ptr<unsigned char[]> prefixOf(const T& full, size_t size) {
  std::unique_ptr<unsigned char[]> block(new unsigned char[size]);
  std::memcpy(block.get(), &full, size);
  const uint32_t structSize = static_cast<uint32_t>(size);
  std::memcpy(block.get(), &structSize, sizeof structSize);
  return block;
}

template <class T>
const T* as(const std::unique_ptr<unsigned char[]>& block) {
  return reinterpret_cast<const T*>(block.get());
}

#define AT(T, field) offsetof(T, field)

TEST(CApiVersionedStruct, AColliderDefCutAtEachFieldTakesTheDefaultsOfTheRest) {
  ScopedWorld w;
  vpColliderDef full = dynamicBall(3.0f);
  full.linearVelocity = vpVec3{1, 0, 0};
  full.mass = 3.0f;
  full.friction = 0.9f;
  full.restitution = 0.4f;
  full.linearDamping = 0.2f;
  full.angularDamping = 0.3f;
  int marker = 0;
  full.userData = &marker;
  full.filter = vpCollisionFilter{2, 3};
  const vpColliderDef defaults = vpDefaultColliderDef();
  using T = vpColliderDef;
  const size_t cuts[] = {AT(T, bodyType),       AT(T, shape),    AT(T, pose),        AT(T, linearVelocity),
                         AT(T, angularVelocity), AT(T, mass),     AT(T, friction),    AT(T, restitution),
                         AT(T, linearDamping),   AT(T, angularDamping), AT(T, userData), AT(T, filter),
                         sizeof(T)};
  for (size_t cut : cuts) {
    SCOPED_TRACE(cut);
    const auto block = prefixOf(full, cut);
    vpColliderId id{};
    ASSERT_VP_OK(vpColliderCreate(w.id, as<T>(block), &id));
    auto given = [cut](size_t offset) { return offset < cut; };
    vpBodyType type;
    ASSERT_VP_OK(vpColliderGetBodyType(id, &type));
    EXPECT_EQ(type, given(AT(T, bodyType)) ? full.bodyType : defaults.bodyType);
    vpTransform pose{};
    ASSERT_VP_OK(vpColliderGetPose(id, &pose));
    EXPECT_EQ(pose.position.y, given(AT(T, pose)) ? full.pose.position.y : defaults.pose.position.y);
    vpBodyProperties p = {sizeof(vpBodyProperties), 0, 0, 0, 0, 0};
    ASSERT_VP_OK(vpColliderGetProperties(id, &p));
    const bool dynamic = type == vpBodyType_Dynamic;
    EXPECT_EQ(p.mass, dynamic ? (given(AT(T, mass)) ? full.mass : defaults.mass) : 0.0f);
    EXPECT_EQ(p.friction, given(AT(T, friction)) ? full.friction : defaults.friction);
    EXPECT_EQ(p.restitution, given(AT(T, restitution)) ? full.restitution : defaults.restitution);
    EXPECT_EQ(p.linearDamping, given(AT(T, linearDamping)) ? full.linearDamping : defaults.linearDamping);
    EXPECT_EQ(p.angularDamping, given(AT(T, angularDamping)) ? full.angularDamping : defaults.angularDamping);
    void* userData = nullptr;
    ASSERT_VP_OK(vpColliderGetUserData(id, &userData));
    EXPECT_EQ(userData, given(AT(T, userData)) ? full.userData : nullptr);
    vpCollisionFilter filter{};
    ASSERT_VP_OK(vpColliderGetCollisionFilter(id, &filter));
    EXPECT_EQ(filter.categoryBits, given(AT(T, filter)) ? 2u : 1u);
    ASSERT_VP_OK(vpColliderDestroy(id));
  }
}

TEST(CApiVersionedStruct, AWorldDefCutAtEachFieldTakesTheDefaultsOfTheRest) {
  vpWorldDef full = unbudgetedWorldDef();
  full.gravity = vpVec3{0, -3, 0};
  full.workerCount = 2;
  using T = vpWorldDef;
  const size_t cuts[] = {AT(T, gravity),  AT(T, workerCount), AT(T, frameBudgetMs), AT(T, rigidMaxSubstep),
                         AT(T, enqueueTask), AT(T, finishTask), AT(T, userTaskContext), AT(T, clock),
                         AT(T, clockContext), AT(T, userData), AT(T, device), sizeof(T)};
  for (size_t cut : cuts) {
    SCOPED_TRACE(cut);
    const auto block = prefixOf(full, cut);
    vpWorldId world{};
    ASSERT_VP_OK(vpWorldCreate(as<T>(block), &world));
    vpVec3 g{};
    ASSERT_VP_OK(vpWorldGetGravity(world, &g));
    EXPECT_EQ(g.y, cut > AT(T, gravity) ? -3.0f : -9.81f);
    ASSERT_VP_OK(vpWorldStep(world, 1.0f / 60.0f));
    vpStepStats stats = vpDefaultStepStats();
    ASSERT_VP_OK(vpWorldGetStepStats(world, &stats));
    EXPECT_EQ(stats.budgetMs, cut > AT(T, frameBudgetMs) ? 0.0f : 16.0f);
    ASSERT_VP_OK(vpWorldDestroy(world));
  }
}

// A def from a header older than `device` gets the CPU: a bad value past the cut is not read.
TEST(CApiVersionedStruct, AWorldDefCutBeforeItsDeviceRunsOnTheCpu) {
  vpWorldDef full = unbudgetedWorldDef();
  full.device = 7;
  vpWorldId world{};
  EXPECT_EQ(vpWorldCreate(&full, &world), vpStatus_InvalidArgument);
  const auto block = prefixOf(full, AT(vpWorldDef, device));
  ASSERT_VP_OK(vpWorldCreate(as<vpWorldDef>(block), &world));
  ASSERT_VP_OK(vpWorldDestroy(world));
}

// Deformable and fluid defs hold pointers with counts: a cut between the two leaves a pointer
// without its count, which validation refuses. What matters is that every cut is accepted as a
// size, nothing past it is read, and each call either creates or names a field.
template <class T, class Create>
void everyCutCreatesOrNamesAField(const T& full, const std::vector<size_t>& cuts, Create create) {
  for (size_t cut : cuts) {
    SCOPED_TRACE(cut);
    const auto block = prefixOf(full, cut);
    const vpStatus s = create(as<T>(block));
    EXPECT_TRUE(s == vpStatus_Ok || s == vpStatus_InvalidArgument) << vpStatusName(s) << ": " << vpGetLastError();
  }
}

TEST(CApiVersionedStruct, DeformableAndFluidDefsCutAtEachFieldAreReadOnlyUpToTheCut) {
  ScopedWorld w;
  static const float vertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const int32_t tet[4] = {0, 1, 2, 3};
  vpDeformableDef deformable = vpDefaultDeformableDef();
  deformable.vertices = vertices;
  deformable.vertexCount = 4;
  deformable.tets = tet;
  deformable.tetCount = 1;
  deformable.filter = vpCollisionFilter{4, 4};
  using D = vpDeformableDef;
  everyCutCreatesOrNamesAField(
      deformable,
      {AT(D, degree), AT(D, vertices), AT(D, vertexCount), AT(D, tets), AT(D, tetCount), AT(D, tetFile),
       AT(D, surfaceFile), AT(D, voxelResolution), AT(D, renderVertices), AT(D, renderVertexCount),
       AT(D, renderTriangles), AT(D, renderTriangleCount), AT(D, pose), AT(D, linearVelocity), AT(D, youngsModulus),
       AT(D, poissonRatio), AT(D, density), AT(D, massDamping), AT(D, stiffnessDamping), AT(D, friction),
       AT(D, solverTolerance), AT(D, solverMaxIterations), AT(D, userData), AT(D, targetResidual), AT(D, priority),
       AT(D, filter), AT(D, surfaceMesher), AT(D, selfCollision), AT(D, meshGrading), sizeof(D)},
      [&](const D* def) {
        vpDeformableId id{};
        return vpDeformableCreate(w.id, def, &id);
      });
  vpFluidDef fluid = vpDefaultFluidDef();
  fluid.resolution[0] = fluid.resolution[1] = fluid.resolution[2] = 4;
  using F = vpFluidDef;
  everyCutCreatesOrNamesAField(
      fluid,
      {AT(F, kind), AT(F, origin), AT(F, resolution), AT(F, cellSize), AT(F, sides), AT(F, density),
       AT(F, advection), AT(F, cflNumber), AT(F, maxSubsteps), AT(F, pressureTolerance),
       AT(F, pressureMaxIterations), AT(F, ambientTemperature), AT(F, densityBuoyancy), AT(F, thermalBuoyancy),
       AT(F, vorticityConfinement), AT(F, densityDissipation), AT(F, temperatureDissipation), AT(F, initialLiquid),
       AT(F, initialLiquidCount), AT(F, emitters), AT(F, emitterCount), AT(F, drains), AT(F, drainCount),
       AT(F, twoWayCoupling), AT(F, userData), AT(F, kinematicViscosity), AT(F, priority), AT(F, filter),
       sizeof(F)},
      [&](const F* def) {
        vpFluidId id{};
        const vpStatus s = vpFluidCreate(w.id, def, &id);
        if (s == vpStatus_Ok) vpFluidDestroy(id);  // the default 32^3 grid is not needed
        return s;
      });
  // The full deformable def and its filter went in.
  vpDeformableId full{};
  ASSERT_VP_OK(vpDeformableCreate(w.id, &deformable, &full));
  vpCollisionFilter filter{};
  ASSERT_VP_OK(vpDeformableGetCollisionFilter(full, &filter));
  EXPECT_EQ(filter.categoryBits, 4u);
}

// The bytes of a struct the library fills, up to `cut`, in a buffer whose rest is a sentinel.
template <class T>
std::vector<unsigned char> sentinelBuffer(size_t cut) {
  std::vector<unsigned char> buffer(sizeof(T), 0xAB);
  const uint32_t structSize = static_cast<uint32_t>(cut);
  std::memcpy(buffer.data(), &structSize, sizeof structSize);
  return buffer;
}

bool untouchedFrom(const std::vector<unsigned char>& buffer, size_t from) {
  for (size_t i = from; i < buffer.size(); ++i)
    if (buffer[i] != 0xAB) return false;
  return true;
}

TEST(CApiVersionedStruct, StatsAndPropertiesAreWrittenUpToTheHostsStructSizeOnly) {
  ScopedWorld w;
  vpColliderDef def = dynamicBall(2.0f);
  def.mass = 5.0f;
  vpColliderId ball{};
  ASSERT_VP_OK(vpColliderCreate(w.id, &def, &ball));
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));

  auto step = sentinelBuffer<vpStepStats>(offsetof(vpStepStats, dt));
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, reinterpret_cast<vpStepStats*>(step.data())));
  uint64_t stepIndex = 0;
  std::memcpy(&stepIndex, step.data() + offsetof(vpStepStats, stepIndex), sizeof stepIndex);
  EXPECT_EQ(stepIndex, 1u);
  EXPECT_TRUE(untouchedFrom(step, offsetof(vpStepStats, dt)));

  auto actor = sentinelBuffer<vpActorStats>(offsetof(vpActorStats, index1));
  ASSERT_VP_OK(vpWorldGetActorStats(w.id, 0, reinterpret_cast<vpActorStats*>(actor.data())));
  vpActorKind kind;
  std::memcpy(&kind, actor.data() + offsetof(vpActorStats, kind), sizeof kind);
  EXPECT_EQ(kind, vpActorKind_Rigid);
  EXPECT_TRUE(untouchedFrom(actor, offsetof(vpActorStats, index1)));
  uint32_t structSize = 0;
  std::memcpy(&structSize, actor.data(), sizeof structSize);
  EXPECT_EQ(structSize, offsetof(vpActorStats, index1));  // the host's own value stays

  auto properties = sentinelBuffer<vpBodyProperties>(offsetof(vpBodyProperties, friction));
  ASSERT_VP_OK(vpColliderGetProperties(ball, reinterpret_cast<vpBodyProperties*>(properties.data())));
  float mass = 0;
  std::memcpy(&mass, properties.data() + offsetof(vpBodyProperties, mass), sizeof mass);
  EXPECT_EQ(mass, 5.0f);
  EXPECT_TRUE(untouchedFrom(properties, offsetof(vpBodyProperties, friction)));

  // Setting from an older header's properties (mass only) keeps the rest as they are.
  vpBodyProperties set = {sizeof(vpBodyProperties), 7.0f, 0.25f, 0, 0, 0};
  const auto block = prefixOf(set, offsetof(vpBodyProperties, friction));
  ASSERT_VP_OK(vpColliderSetProperties(ball, as<vpBodyProperties>(block)));
  vpBodyProperties now = {sizeof(vpBodyProperties), 0, 0, 0, 0, 0};
  ASSERT_VP_OK(vpColliderGetProperties(ball, &now));
  EXPECT_EQ(now.mass, 7.0f);
  EXPECT_EQ(now.friction, def.friction);
}

TEST(CApiVersionedStruct, ANewerOrTornStructSizeIsAVersionMismatchNamingTheStruct) {
  ScopedWorld w;
  struct Case {
    uint32_t size;
    const char* message;
  } cases[] = {
      {sizeof(vpColliderDef) + 8, "vpColliderDef.structSize = "},  // a newer header
      {offsetof(vpColliderDef, mass) + 2, "vpColliderDef.structSize = "},  // inside a field
      {0, "vpColliderDef.structSize = 0"},
      {2, "vpColliderDef.structSize = 2"},
  };
  for (const Case& c : cases) {
    std::vector<unsigned char> block(std::max<size_t>(c.size, sizeof(vpColliderDef)));
    vpColliderDef def = vpDefaultColliderDef();
    std::memcpy(block.data(), &def, sizeof def);
    std::memcpy(block.data(), &c.size, sizeof c.size);
    vpColliderId id{};
    EXPECT_EQ(vpColliderCreate(w.id, reinterpret_cast<const vpColliderDef*>(block.data()), &id),
              vpStatus_VersionMismatch);
    EXPECT_TRUE(lastErrorContains(c.message)) << vpGetLastError();
  }
  EXPECT_EQ(vpColliderCreate(w.id, nullptr, nullptr), vpStatus_InvalidArgument);
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetColliderCount(w.id, &count));
  EXPECT_EQ(count, 0);
  vpStepStats stats = vpDefaultStepStats();
  stats.structSize = sizeof(vpStepStats) + 4;
  EXPECT_EQ(vpWorldGetStepStats(w.id, &stats), vpStatus_VersionMismatch);
  EXPECT_TRUE(lastErrorContains("vpStepStats.structSize")) << vpGetLastError();
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  vpActorStats actor{};  // structSize 0: a host that forgot vpDefaultActorStats()
  EXPECT_EQ(vpWorldGetActorStats(w.id, 0, &actor), vpStatus_VersionMismatch);
  EXPECT_TRUE(lastErrorContains("vpActorStats.structSize = 0")) << vpGetLastError();
}

}  // namespace
