// The hydrostatic pressure under a liquid's free surface (fluid/surface/hydrostatic_pressure.h)
// and the loads it puts on a body, by the same rules as the pressure's loads: rho g times the
// depth below a flat surface, at any depth (the level set is a distance clamped beyond its
// band, the columns' surfaces are not), along whichever grid axis gravity points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "collide/shape_display_mesh.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/pressure_forces.h"
#include "fluid/solids/surface_pressure_load.h"
#include "fluid/surface/hydrostatic_pressure.h"
#include "liquid_tank_world.h"

namespace vp {
namespace {

constexpr double kDensity = 1000.0, kG = 9.81;
constexpr int kCells = 24;

struct FlatLiquid {
  MacGrid grid;
  Array<double> phi;
};

// A 1 m box of kCells^3 cells whose level set is the signed distance `distance(centre)`,
// clamped to four cells as redistancing leaves it.
template <class Distance>
FlatLiquid flatLiquid(const Distance& distance) {
  FlatLiquid l;
  l.grid.spec.origin = Vec3::Zero();
  l.grid.spec.h = 1.0 / kCells;
  l.grid.spec.nx = l.grid.spec.ny = l.grid.spec.nz = kCells;
  l.phi.resize(static_cast<size_t>(l.grid.cellCount()));
  const double band = 4.0 * l.grid.spec.h;
  for (int k = 0; k < kCells; ++k)
    for (int j = 0; j < kCells; ++j)
      for (int i = 0; i < kCells; ++i)
        l.phi[l.grid.cellIndex(i, j, k)] = std::clamp(distance(l.grid.cellCentre(i, j, k)), -band, band);
  return l;
}

const Aabb kWholeBox{Vec3::Zero(), Vec3::Ones()};

TEST(HydrostaticPressure, IsRhoGTimesTheDepthBelowAFlatSurfaceAtAnyDepth) {
  const FlatLiquid l = flatLiquid([](const Vec3& x) { return x.y() - 0.7; });
  const HydrostaticPressure p(l.grid, l.phi.data(), kDensity, Vec3(0.0, -kG, 0.0), kWholeBox);
  for (double y : {0.05, 0.3, 0.69, 0.7, 0.71, 0.95})
    EXPECT_NEAR(p.at(Vec3(0.43, y, 0.61)), kDensity * kG * std::max(0.0, 0.7 - y), 1e-9 * kDensity * kG) << y;
}

TEST(HydrostaticPressure, FollowsGravityAlongAnyGridAxis) {
  // Gravity along +x: the liquid lies against the high x side, its surface at x = 0.3.
  const FlatLiquid l = flatLiquid([](const Vec3& x) { return 0.3 - x.x(); });
  const HydrostaticPressure p(l.grid, l.phi.data(), kDensity, Vec3(kG, 0.0, 0.0), kWholeBox);
  for (double x : {0.1, 0.29, 0.31, 0.6, 0.97})
    EXPECT_NEAR(p.at(Vec3(x, 0.2, 0.8)), kDensity * kG * std::max(0.0, x - 0.3), 1e-9 * kDensity * kG) << x;
}

// An axis-aligned box's surface as its display mesh, centred at `centre`.
void boxSurface(const Vec3& halfExtents, const Vec3& centre, Array<Eigen::Vector3d>* vertices,
                Array<Eigen::Vector3i>* triangles) {
  ShapeDesc box;
  box.type = ShapeType::Box;
  box.halfExtents = halfExtents;
  const ShapeDisplayMesh mesh = buildShapeDisplayMesh(box);
  vertices->clear();
  triangles->clear();
  for (const Vec3& p : mesh.positions) vertices->push_back(p + centre);
  for (const auto& t : mesh.triangles) triangles->emplace_back(t[0], t[1], t[2]);
}

Vec3 sum(const Array<Vec3>& forces) {
  Vec3 s = Vec3::Zero();
  for (const Vec3& f : forces) s += f;
  return s;
}

// Archimedes on a deformable's surface: the weight of the liquid it displaces, whole under the
// surface and cut by it (its bottom alone is wet then; the sides' forces cancel). The pressure is
// linear below the surface, which the pieces' midpoint rule integrates exactly.
TEST(HydrostaticPressure, OnAClosedSurfaceIsTheWeightOfTheLiquidItDisplaces) {
  const FlatLiquid l = flatLiquid([](const Vec3& x) { return x.y() - 0.7; });
  const Vec3 half(0.1, 0.05, 0.15);
  const double volume = 8.0 * half.prod();
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  for (double centreY : {0.3, 0.7}) {
    Array<Eigen::Vector3d> vertices;
    Array<Eigen::Vector3i> triangles;
    boxSurface(half, Vec3(0.52, centreY, 0.47), &vertices, &triangles);
    Array<Vec3> forces;
    surfaceHydrostaticLoad(*tasks, l.grid, l.phi.data(), kDensity, Vec3(0.0, -kG, 0.0), vertices, triangles, &forces);
    const double submerged = centreY == 0.7 ? 0.5 : 1.0;
    const Vec3 expected(0.0, kDensity * kG * volume * submerged, 0.0);
    EXPECT_LT((sum(forces) - expected).norm(), 1e-9 * expected.norm()) << centreY;
  }
}

// In a still tank the pressure is hydrostatic, so a fluid step hands a rigid body almost no
// dynamic load: the hydrostatic part it takes out, by the same sums over the faces the body
// covers, is nearly the whole of it, and the body takes its buoyancy anew at its own steps. One
// step from rest (the solid displaces the liquid, which then moves). What remains comes from
// the faces the waterline cuts inside the body: the columns through it cross where the level
// set extended inside the solid does, not quite where the surface around it lies (2.7% of the
// buoyancy measured here; the bound keeps it a small part, not the whole). A deformable's surface form integrates the pressure itself, which such a
// column's surface offsets: there the held dynamic part keeps more of the buoyancy (a sixth
// for a floating block, README "Deformables in fluids").
TEST(HydrostaticPressure, AStillTanksStepHandsARigidBodyAlmostNoDynamicLoad) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double fill = 0.6;
  FluidDesc d = testutil::liquidTank(kCells, kCells, kCells, 1.0 / kCells, fill);
  d.sides[3] = DomainSide::Open;
  std::unique_ptr<FluidActor> actor;
  ASSERT_EQ(FluidActor::create(d, *tasks, &actor), Status::Ok) << lastError();
  ColliderShape box;
  box.kind = ShapeKind::Box;
  box.halfExtents = Vec3(0.12, 0.06, 0.1);
  box.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vec3::UnitZ()));
  box.translation = Vec3(0.3, fill, 0.5);
  PreparedCollider rigid;
  ASSERT_EQ(prepareCollider(box, &rigid), Status::Ok);
  FluidStepInput input;
  input.gravity = Vec3(0.0, -kG, 0.0);
  input.tasks = tasks.get();
  input.colliders = {FluidCollider{1, 1, &rigid, nullptr, true, {}}};
  ActorStats stats;
  actor->step(input, &stats, nullptr);
  ASSERT_EQ(actor->loads().size(), 1u);
  const PressureLoad weight = actor->hydrostaticColliderLoad(input.gravity, rigid);
  const PressureLoad& dynamic = actor->loads()[0].load;
  std::printf("buoyancy %.3f N; dynamic part %.2e N, %.2e N m\n", weight.force.y(), dynamic.force.norm(),
              dynamic.torque.norm());
  EXPECT_GT(weight.force.y(), 0.0);
  EXPECT_LT(dynamic.force.norm(), 0.05 * weight.force.y());
  EXPECT_LT(dynamic.torque.norm(), 0.05 * weight.force.y() * box.halfExtents.norm());
}

}  // namespace
}  // namespace vp
