// Fluid actors through the C ABI.
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "capi_test_support.h"
#include "raw_enum_calls.h"

namespace {

vpFluidDef smallSmoke() {
  vpFluidDef d = vpDefaultFluidDef();
  d.resolution[0] = d.resolution[1] = d.resolution[2] = 16;
  d.cellSize = 1.0f / 16.0f;
  d.density = 1.2f;
  d.sides[3] = vpDomainSide_Open;
  return d;
}

TEST(CApiFluid, SmokeWithAnEmitterAndASphereRisesAndReportsStats) {
  ScopedWorld w;
  vpColliderDef sphere = vpDefaultColliderDef();
  sphere.shape.radius = 0.12f;
  sphere.pose.position = vpVec3{0.5f, 0.6f, 0.5f};
  vpColliderId ball{};
  ASSERT_VP_OK(vpColliderCreate(w.id, &sphere, &ball));
  vpFluidEmitter emitter{};
  emitter.region.type = vpRegionType_Sphere;
  emitter.region.centre = vpVec3{0.5f, 0.15f, 0.5f};
  emitter.region.radius = 0.1f;
  emitter.velocity = vpVec3{0, 0.5f, 0};
  emitter.densityRate = 1.0f;
  emitter.temperature = 2.0f;
  vpFluidDef def = smallSmoke();
  def.emitters = &emitter;
  def.emitterCount = 1;
  vpFluidId fluid{};
  ASSERT_VP_OK(vpFluidCreate(w.id, &def, &fluid));
  for (int i = 0; i < 20; ++i) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));

  int32_t nx = 0, ny = 0, nz = 0;
  ASSERT_VP_OK(vpFluidGetResolution(fluid, &nx, &ny, &nz));
  EXPECT_EQ(nx * ny * nz, 16 * 16 * 16);
  std::vector<float> smoke(static_cast<size_t>(nx) * ny * nz), velocity(3 * smoke.size());
  ASSERT_VP_OK(vpFluidGetField(fluid, vpFluidField_SmokeDensity, smoke.data(), static_cast<int64_t>(smoke.size())));
  ASSERT_VP_OK(vpFluidGetVelocityGrid(fluid, velocity.data(), static_cast<int64_t>(smoke.size())));
  double total = 0.0;
  for (float s : smoke) total += s;
  float amount = 0.0f;
  ASSERT_VP_OK(vpFluidGetAmount(fluid, &amount));
  EXPECT_NEAR(amount, total / (16.0 * 16 * 16), 1e-4 * amount);
  EXPECT_GT(amount, 0.0f);
  vpVec3 probe{0.5f, 0.35f, 0.5f}, v{};
  ASSERT_VP_OK(vpFluidSampleVelocity(fluid, &probe, 1, &v));
  EXPECT_GT(v.y, 0.1f);

  vpActorStats stats = vpDefaultActorStats();
  ASSERT_VP_OK(vpFluidGetStats(fluid, &stats));
  EXPECT_EQ(stats.kind, vpActorKind_Fluid);
  EXPECT_GT(stats.phases[vpPhase_Pressure].iterations, 0);
  EXPECT_GT(stats.phases[vpPhase_Advect].ms, 0.0f);
  vpStepStats step = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &step));
  EXPECT_EQ(step.actorCount, 2);  // rigid + fluid

  int32_t vertices = -1, triangles = -1;
  ASSERT_VP_OK(vpFluidGetSurfaceMeshSize(fluid, &vertices, &triangles));
  EXPECT_EQ(vertices, 0);  // smoke has no surface
  vpFluidId found{};
  ASSERT_VP_OK(vpFluidDestroy(fluid));
  EXPECT_EQ(vpFluidIsValid(fluid), vpStatus_InvalidId);
  EXPECT_EQ(vpFluidGetAmount(fluid, &amount), vpStatus_InvalidId);
  EXPECT_EQ(vpWorldFindFluid(w.id, "none", &found), vpStatus_InvalidArgument);
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
}

TEST(CApiFluid, BadDefinitionsNameTheFieldAndCreateNothing) {
  ScopedWorld w;
  vpFluidEmitter emitter{};
  emitter.region.type = vpRegionType_Box;
  emitter.region.halfExtents = vpVec3{0.1f, 0.1f, 0.1f};
  struct Case {
    const char* field;
    void (*edit)(vpFluidDef&, vpFluidEmitter*);
  } cases[] = {
      {"kind = 9", [](vpFluidDef& d, vpFluidEmitter*) { setRawEnum(d.kind, 9); }},
      {"resolution.z = 0", [](vpFluidDef& d, vpFluidEmitter*) { d.resolution[2] = 0; }},
      {"cellSize = -1", [](vpFluidDef& d, vpFluidEmitter*) { d.cellSize = -1.0f; }},
      {"sides[5] = 3", [](vpFluidDef& d, vpFluidEmitter*) { setRawEnum(d.sides[5], 3); }},
      {"advection = 4", [](vpFluidDef& d, vpFluidEmitter*) { setRawEnum(d.advection, 4); }},
      {"origin = (nan", [](vpFluidDef& d, vpFluidEmitter*) { d.origin.x = NAN; }},
      {"origin = (1e+30", [](vpFluidDef& d, vpFluidEmitter*) { d.origin.x = 1e30f; }},
      {"cellSize = 1e-30", [](vpFluidDef& d, vpFluidEmitter*) { d.cellSize = 1e-30f; }},
      {"density = 9.99995e-41", [](vpFluidDef& d, vpFluidEmitter*) { d.density = 1e-40f; }},
      {"emitters is NULL", [](vpFluidDef& d, vpFluidEmitter*) { d.emitterCount = 2; }},
      {"emitterCount = -1", [](vpFluidDef& d, vpFluidEmitter*) { d.emitterCount = -1; }},
      {"emitters[0].region.type = 5", [](vpFluidDef& d, vpFluidEmitter* e) {
         setRawEnum(e->region.type, 5);
         d.emitters = e;
         d.emitterCount = 1;
       }},
      {"emitters[0].region.halfExtents", [](vpFluidDef& d, vpFluidEmitter* e) {
         e->region.halfExtents.y = 0.0f;
         d.emitters = e;
         d.emitterCount = 1;
       }},
      {"pressureTolerance = 0", [](vpFluidDef& d, vpFluidEmitter*) { d.pressureTolerance = 0.0f; }},
      {"priority = 1000001: must be in [-1000000, 1000000]",
       [](vpFluidDef& d, vpFluidEmitter*) { d.priority = 1000001; }},
      {"priority = -1000001: must be in [-1000000, 1000000]",
       [](vpFluidDef& d, vpFluidEmitter*) { d.priority = -1000001; }},
      {"vpFluidDef.structSize = 6", [](vpFluidDef& d, vpFluidEmitter*) { d.structSize = 6; }},
  };
  for (const Case& c : cases) {
    vpFluidDef def = smallSmoke();
    vpFluidEmitter e = emitter;
    c.edit(def, &e);
    vpFluidId id{};
    EXPECT_NE(vpFluidCreate(w.id, &def, &id), vpStatus_Ok) << c.field;
    EXPECT_TRUE(lastErrorContains(c.field)) << "expected '" << c.field << "' in: " << vpGetLastError();
    EXPECT_TRUE(vpFluidIdIsNull(id));
  }
  vpStepStats step = vpDefaultStepStats();
  ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  ASSERT_VP_OK(vpWorldGetStepStats(w.id, &step));
  EXPECT_EQ(step.actorCount, 1);  // only the rigid pseudo-actor: nothing was created
}

TEST(CApiFluid, PriorityIsAppendedAndDefaultsToZero) {
  static_assert(offsetof(vpFluidDef, priority) > offsetof(vpFluidDef, kinematicViscosity),
                "appended after the older fields");
  EXPECT_EQ(vpDefaultFluidDef().priority, 0);
  ScopedWorld w;
  vpFluidDef def = smallSmoke();
  def.priority = -1000000;  // the bound itself is accepted
  vpFluidId id{};
  EXPECT_VP_OK(vpFluidCreate(w.id, &def, &id));
}

TEST(CApiFluid, GettersCheckCapacitiesAndArguments) {
  ScopedWorld w;
  vpFluidDef def = smallSmoke();
  vpFluidId fluid{};
  ASSERT_VP_OK(vpFluidCreate(w.id, &def, &fluid));
  std::vector<float> small(10);
  EXPECT_EQ(vpFluidGetField(fluid, vpFluidField_Pressure, small.data(), 10), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("capacity = 10"));
  std::vector<float> cells(16 * 16 * 16);
  // A C host may pass any int as the enum: the call is made from C (raw_enum_calls.c).
  EXPECT_EQ(rawFluidGetField(fluid, 42, cells.data(), 4096), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("field = 42"));
  vpVec3 nanPoint{NAN, 0, 0}, out{};
  EXPECT_EQ(vpFluidSampleVelocity(fluid, &nanPoint, 1, &out), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("points[0]"));
  EXPECT_EQ(vpFluidSampleVelocity(fluid, nullptr, 1, &out), vpStatus_InvalidArgument);
  vpFluidId foreign = fluid;
  foreign.world.generation += 1;
  EXPECT_EQ(vpFluidIsValid(foreign), vpStatus_InvalidId);
}

TEST(CApiFluid, KindAndDomainAreThoseOfTheDefinition) {
  ScopedWorld w;
  vpFluidDef def = smallSmoke();
  def.kind = vpFluidKind_Liquid;
  def.origin = vpVec3{-1.0f, 0.5f, 2.0f};
  def.cellSize = 0.125f;
  vpFluidId fluid{};
  ASSERT_VP_OK(vpFluidCreate(w.id, &def, &fluid));
  vpFluidKind kind = vpFluidKind_Smoke;
  vpVec3 origin{};
  float cellSize = 0.0f;
  ASSERT_VP_OK(vpFluidGetKind(fluid, &kind));
  ASSERT_VP_OK(vpFluidGetDomain(fluid, &origin, &cellSize));
  EXPECT_EQ(kind, vpFluidKind_Liquid);
  EXPECT_EQ(origin.x, -1.0f);
  EXPECT_EQ(origin.y, 0.5f);
  EXPECT_EQ(origin.z, 2.0f);
  EXPECT_EQ(cellSize, 0.125f);
  ASSERT_VP_OK(vpFluidGetDomain(fluid, nullptr, nullptr));  // every output is optional
  vpFluidDef smoke = smallSmoke();
  vpFluidId other{};
  ASSERT_VP_OK(vpFluidCreate(w.id, &smoke, &other));
  ASSERT_VP_OK(vpFluidGetKind(other, &kind));
  EXPECT_EQ(kind, vpFluidKind_Smoke);
  ASSERT_VP_OK(vpFluidDestroy(fluid));
  EXPECT_EQ(vpFluidGetKind(fluid, &kind), vpStatus_InvalidId);
  EXPECT_EQ(vpFluidGetDomain(fluid, &origin, &cellSize), vpStatus_InvalidId);
}

TEST(CApiFluid, WorldListsItsFluidsInSlotOrder) {
  ScopedWorld w;
  vpFluidDef def = smallSmoke();
  def.resolution[0] = def.resolution[1] = def.resolution[2] = 4;
  vpFluidId a{}, b{}, c{};
  ASSERT_VP_OK(vpFluidCreate(w.id, &def, &a));
  ASSERT_VP_OK(vpFluidCreate(w.id, &def, &b));
  ASSERT_VP_OK(vpFluidCreate(w.id, &def, &c));
  ASSERT_VP_OK(vpFluidDestroy(b));
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetFluidCount(w.id, &count));
  ASSERT_EQ(count, 2);
  vpFluidId ids[3] = {};
  ASSERT_VP_OK(vpWorldGetFluids(w.id, ids, 3, &count));
  ASSERT_EQ(count, 2);
  EXPECT_TRUE(ids[0].index1 == a.index1 && ids[0].generation == a.generation);
  EXPECT_TRUE(ids[1].index1 == c.index1 && ids[1].generation == c.generation);
  EXPECT_EQ(vpFluidIsValid(ids[1]), vpStatus_Ok);
  ASSERT_VP_OK(vpWorldGetFluids(w.id, ids, 1, &count));  // a short buffer gets a prefix
  EXPECT_EQ(count, 1);
  EXPECT_EQ(vpWorldGetFluids(w.id, nullptr, 2, &count), vpStatus_InvalidArgument);
  EXPECT_EQ(vpWorldGetFluids(w.id, ids, -1, &count), vpStatus_InvalidArgument);
  EXPECT_EQ(vpWorldGetFluidCount(w.id, nullptr), vpStatus_InvalidArgument);
  EXPECT_EQ(vpWorldGetFluidCount(vpWorldId{}, &count), vpStatus_InvalidId);
}

// The viscosity is the one vpFluidDef field appended after userData: a bad value must be
// caught by name (not read as garbage) and leave the world as it was.
TEST(CApiFluid, BadViscosityIsNamedAndChangesNothing) {
  ScopedWorld w;
  vpFluidDef def = smallSmoke();
  def.kind = vpFluidKind_Liquid;
  def.resolution[0] = def.resolution[1] = def.resolution[2] = 8;
  def.cellSize = 0.125f;
  vpFluidRegion water{};
  water.type = vpRegionType_Box;
  water.centre = vpVec3{0.25f, 0.5f, 0.5f};  // a column that collapses: a liquid at rest has nothing to diffuse
  water.halfExtents = vpVec3{0.25f, 0.5f, 0.5f};
  def.initialLiquid = &water;
  def.initialLiquidCount = 1;
  EXPECT_EQ(vpDefaultFluidDef().kinematicViscosity, 0.0f);
  def.kinematicViscosity = 0.05f;
  vpFluidId viscous{};
  ASSERT_VP_OK(vpFluidCreate(w.id, &def, &viscous));
  for (int s = 0; s < 3; ++s) ASSERT_VP_OK(vpWorldStep(w.id, 1.0f / 60.0f));
  vpActorStats before = vpDefaultActorStats();
  ASSERT_VP_OK(vpFluidGetStats(viscous, &before));
  EXPECT_GT(before.phases[vpPhase_Viscosity].iterations, 0);
  const struct {
    float value;
    const char* message;
  } cases[] = {{-1.0f, "kinematicViscosity = -1"},
               {NAN, "kinematicViscosity = nan"},
               {INFINITY, "kinematicViscosity = inf"},
               {11.0f, "kinematicViscosity = 11: must be in [0, 10]"}};
  for (const auto& c : cases) {
    vpFluidDef bad = def;
    bad.kinematicViscosity = c.value;
    vpFluidId id{};
    EXPECT_EQ(vpFluidCreate(w.id, &bad, &id), vpStatus_InvalidArgument) << c.message;
    EXPECT_TRUE(lastErrorContains(c.message)) << "expected '" << c.message << "' in: " << vpGetLastError();
    EXPECT_TRUE(vpFluidIdIsNull(id));
  }
  int32_t count = -1;
  ASSERT_VP_OK(vpWorldGetFluidCount(w.id, &count));
  EXPECT_EQ(count, 1);
  vpActorStats after = vpDefaultActorStats();
  ASSERT_VP_OK(vpFluidGetStats(viscous, &after));
  EXPECT_EQ(after.phases[vpPhase_Viscosity].iterations, before.phases[vpPhase_Viscosity].iterations);
}

}  // namespace
