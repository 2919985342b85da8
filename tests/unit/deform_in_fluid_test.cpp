// Deformables in fluids, two-way: the fluid sees a deformable's surface as a moving solid
// (exact fractions, the surface's velocity), and its pressure acts on the surface's nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "deform/fluid_immersion.h"
#include "fluid/solids/face_fraction_field.h"
#include "fluid/solids/solid_motion_history.h"
#include "fluid/solids/viscous_traction.h"
#include "fluid/viscosity.h"
#include "geometry/box_tet_mesh.h"
#include "geometry/isosurface_stuffing.h"
#include "geometry_test_shapes.h"
#include "liquid_tank_world.h"
#include "spin_down_check.h"
#include "viscous_exchange_step.h"
#include "world.h"

namespace vp {
namespace {

using testutil::meanSurfaceHeight;
using testutil::worldWithOpenTank;

// A jelly block of 0.3 x 0.2 x 0.3 m (flat: a half-density cube upright would roll over),
// lowest face at `bottom`, centred over (0.5, 0.5) in x and z.
DeformableDesc jellyBlock(double density, double bottom) {
  DeformableDesc d;
  d.mesh = makeBoxTetMesh({3, 2, 3}, Vec3(0.3, 0.2, 0.3), Vec3(0.35, bottom, 0.35));
  d.material.youngsModulus = 2e5;
  d.material.poissonRatio = 0.3;
  d.material.density = density;
  d.solver.tolerance = 1e-6;
  d.solver.maxIterations = 500;
  return d;
}

struct JellyMotion {
  Vec3 centre = Vec3::Zero(), velocity = Vec3::Zero();
  double bottom = 0.0, top = 0.0;
};

JellyMotion motionOf(const DeformableBody& body) {
  JellyMotion m;
  double mass = 0.0;
  m.bottom = 1e30, m.top = -1e30;
  for (int32_t i = 0; i < body.nodeCount(); ++i) {
    const double mi = body.nodeMasses()[i];
    const Vec3 x(body.positions()[3 * i], body.positions()[3 * i + 1], body.positions()[3 * i + 2]);
    const Vec3 v(body.velocities()[3 * i], body.velocities()[3 * i + 1], body.velocities()[3 * i + 2]);
    m.centre += mi * x;
    m.velocity += mi * v;
    mass += mi;
    m.bottom = std::min(m.bottom, x.y());
    m.top = std::max(m.top, x.y());
  }
  m.centre /= mass;
  m.velocity /= mass;
  return m;
}

// The coupling's work is a stats phase of its own: a tank with a jelly falling into it spends
// Coupling time every frame (the jelly's fractions and its loads), and so does the jelly
// (taking the loads, refreshing the surface the tank sees); the same tank whose filter leaves
// the jelly out, beside a static collider, spends none, and its fractions stay in the
// Fractions phase.
TEST(DeformableInFluid, TheCouplingsWorkIsAStatsPhaseOfItsOwn) {
  constexpr uint32_t kUnseen = 2;
  for (const bool seen : {true, false}) {
    FluidHandle fluid;
    std::unique_ptr<World> world = testutil::unbudgetedWorld();
    ASSERT_TRUE(world);
    FluidDesc d = testutil::liquidTank(16, 16, 16, 1.0 / 16, 0.5);
    d.sides[3] = DomainSide::Open;
    d.filter.mask = ~kUnseen;
    ASSERT_EQ(world->createFluid(d, &fluid), Status::Ok) << lastError();
    ColliderDesc post;
    post.bodyType = BodyType::Static;
    post.shape.type = ShapeType::Box;
    post.shape.halfExtents = Vec3(0.05, 0.3, 0.05);
    post.pose.position = Vec3(0.15, 0.3, 0.15);
    ColliderHandle postHandle;
    ASSERT_EQ(world->createCollider(post, &postHandle), Status::Ok) << lastError();
    DeformableDesc jelly = jellyBlock(500.0, 0.55);
    if (!seen) jelly.filter.category = kUnseen;
    DeformableHandle jellyHandle;
    ASSERT_EQ(world->createDeformable(std::move(jelly), &jellyHandle), Status::Ok) << lastError();
    for (int frame = 0; frame < 20; ++frame) {
      ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok) << lastError();
      const ActorStats *f = nullptr, *body = nullptr;
      for (const ActorStats& a : world->lastStats().actors)
        if (a.kind == ActorKind::Fluid) f = &a;
        else if (a.kind == ActorKind::Deformable) body = &a;
      ASSERT_NE(f, nullptr);
      ASSERT_NE(body, nullptr);
      if (seen) {
        EXPECT_GT(f->phase(Phase::Coupling).ms, 0.0) << "frame " << frame;
        EXPECT_GT(body->phase(Phase::Coupling).ms, 0.0) << "frame " << frame;
        EXPECT_LE(body->phase(Phase::Coupling).ms, body->totalMs) << "frame " << frame;
      } else {
        EXPECT_EQ(f->phase(Phase::Coupling).ms, 0.0) << "frame " << frame;
      }
      EXPECT_GT(f->phase(Phase::Fractions).ms, 0.0) << "frame " << frame;
    }
  }
}

// The fluid sees the deformable's surface exactly as a rigid mesh of the same triangles: at
// rest, the same fractions, face for face.
TEST(DeformableInFluid, ASurfaceAtRestGivesTheFractionsOfTheSameRigidMesh) {
  std::unique_ptr<DeformableBody> body;
  DeformableDesc d = jellyBlock(500.0, 0.33);
  ASSERT_EQ(DeformableBody::create(d, &body), Status::Ok) << lastError();
  const std::shared_ptr<const PreparedCollider> surface = body->fluidSurface();
  ColliderShape rigid;
  rigid.kind = ShapeKind::TriangleMesh;
  rigid.meshVertices = surface->shape.meshVertices;
  rigid.meshTriangles = surface->shape.meshTriangles;
  PreparedCollider prepared;
  ASSERT_EQ(prepareCollider(rigid, &prepared), Status::Ok) << lastError();
  MacGridSpec grid;
  grid.h = 1.0 / 24;
  grid.nx = grid.ny = grid.nz = 24;
  FaceFractionField a, b;
  ASSERT_EQ(initFaceFractionField(grid, &a), Status::Ok);
  ASSERT_EQ(initFaceFractionField(grid, &b), Status::Ok);
  const PreparedCollider* deforming = surface.get();
  const PreparedCollider* fixed = &prepared;
  ASSERT_EQ(computeFaceFractions(&deforming, 1, &a), Status::Ok);
  ASSERT_EQ(computeFaceFractions(&fixed, 1, &b), Status::Ok);
  int cut = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (size_t f = 0; f < a.open[axis].size(); ++f) {
      ASSERT_NEAR(a.open[axis][f], b.open[axis][f], 1e-9);
      ASSERT_EQ(a.solidVelocity[axis][f], 0.0);
      cut += a.open[axis][f] < 1.0;
    }
  EXPECT_GT(cut, 100);  // the block covers faces
}

// A surface moving by translation carries its velocity onto the faces it covers.
TEST(DeformableInFluid, ATranslatingSurfaceGivesItsVelocityToTheFacesItCovers) {
  std::unique_ptr<DeformableBody> body;
  DeformableDesc d = jellyBlock(500.0, 0.33);
  d.linearVelocity = Vec3(0.0, -0.7, 0.2);
  ASSERT_EQ(DeformableBody::create(d, &body), Status::Ok) << lastError();
  const std::shared_ptr<const PreparedCollider> surface = body->fluidSurface();
  MacGridSpec grid;
  grid.h = 1.0 / 24;
  grid.nx = grid.ny = grid.nz = 24;
  FaceFractionField field;
  ASSERT_EQ(initFaceFractionField(grid, &field), Status::Ok);
  const PreparedCollider* deforming = surface.get();
  ASSERT_EQ(computeFaceFractions(&deforming, 1, &field), Status::Ok);
  for (int axis = 0; axis < 3; ++axis)
    for (size_t f = 0; f < field.open[axis].size(); ++f)
      if (field.open[axis][f] < 1.0) {
        ASSERT_NEAR(field.solidVelocity[axis][f], d.linearVelocity[axis], 1e-12);
      }
}

// jellyBlock(500, 0.33)'s surface with vertex velocities velocityAt(x), and its fractions on a
// 48^3 grid of 1 m.
struct MovingBlock {
  PreparedCollider surface;
  MacGridSpec grid;
  FaceFractionField field;
};

void fractionsOfMovingBlock(const std::function<Vec3(const Vec3&)>& velocityAt, MovingBlock* out) {
  std::unique_ptr<DeformableBody> body;
  ASSERT_EQ(DeformableBody::create(jellyBlock(500.0, 0.33), &body), Status::Ok) << lastError();
  out->surface = *body->fluidSurface();
  Array<Vec3> velocities;
  for (const Vec3& x : out->surface.shape.meshVertices) velocities.push_back(velocityAt(x));
  setDeformingSurface(&out->surface, out->surface.shape.meshVertices, velocities);
  out->grid.h = 1.0 / 48;
  out->grid.nx = out->grid.ny = out->grid.nz = 48;
  ASSERT_EQ(initFaceFractionField(out->grid, &out->field), Status::Ok);
  const PreparedCollider* deforming = &out->surface;
  ASSERT_EQ(computeFaceFractions(&deforming, 1, &out->field), Status::Ok);
}

// A face the surface cuts takes the surface's velocity where the surface crosses it: the mean
// over its trace on the face. With a velocity linear in position (a shear, so that the normal
// component varies across the face), that mean is the velocity at the trace's centroid; the
// block's flat sides cut each face plane in a rectangle, whose sides clipped to the face are
// the trace.
TEST(DeformableInFluid, ACutFaceTakesTheVelocityOfTheSurfaceWhereItCrossesTheFace) {
  const Vec3 lo(0.35, 0.33, 0.35), hi(0.65, 0.53, 0.65);  // jellyBlock(_, 0.33)'s corners
  const Vec3 centre = 0.5 * (lo + hi);
  auto velocityAt = [&](const Vec3& x) { return Vec3(x.y() - centre.y(), x.z() - centre.z(), x.x() - centre.x()); };
  MovingBlock block;
  ASSERT_NO_FATAL_FAILURE(fractionsOfMovingBlock(velocityAt, &block));
  const FaceFractionField& field = block.field;
  int cut = 0;
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const Eigen::Vector3i d = field.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const size_t f = field.faceIndex(a, i, j, k);
          if (!(field.open[a][f] > 0.0 && field.open[a][f] < 1.0)) continue;
          const AxisFace face = field.face(a, i, j, k);
          const double r = 0.5 * face.h;
          const double faceLo[2] = {face.centre[u] - r, face.centre[v] - r};
          const double faceHi[2] = {face.centre[u] + r, face.centre[v] + r};
          // The rectangle's four sides (side s at coordinate `at` of direction `across`, running
          // along the other one), each clipped to the face.
          double length = 0.0;
          Vec3 moment = Vec3::Zero();
          for (int across = 0; across < 2; ++across)
            for (const double at : {across == 0 ? lo[u] : lo[v], across == 0 ? hi[u] : hi[v]}) {
              const int along = 1 - across, alongAxis = along == 0 ? u : v;
              if (at < faceLo[across] || at > faceHi[across]) continue;
              const double from = std::max(lo[alongAxis], faceLo[along]), to = std::min(hi[alongAxis], faceHi[along]);
              if (to <= from) continue;
              Vec3 mid = face.centre;
              mid[across == 0 ? u : v] = at;
              mid[alongAxis] = 0.5 * (from + to);
              length += to - from;
              moment += (to - from) * mid;
            }
          ASSERT_GT(length, 0.0) << "axis " << a << " face " << i << ", " << j << ", " << k;
          ASSERT_NEAR(field.solidVelocity[a][f], velocityAt(moment / length)[a], 1e-12)
              << "axis " << a << " face " << i << ", " << j << ", " << k;
          ++cut;
        }
  }
  EXPECT_GT(cut, 500);
}

// A deforming surface's velocities: a face it covers whole that borders a cell with an open
// face (one the fluid may read) takes the nearest surface point's velocity; a face whose cells
// are covered whole takes the surface's mean vertex velocity (no fluid cell reads it).
TEST(DeformableInFluid, InteriorFacesTakeTheMeanVelocityAndFacesBesideFluidTheNearestPoints) {
  // An expansion about the block's centre: every vertex has its own velocity.
  const Vec3 centre(0.5, 0.43, 0.5);
  MovingBlock block;
  ASSERT_NO_FATAL_FAILURE(fractionsOfMovingBlock([&](const Vec3& x) { return Vec3(x - centre); }, &block));
  const PreparedCollider& surface = block.surface;
  const MacGridSpec& grid = block.grid;
  const FaceFractionField& field = block.field;
  auto cellOpen = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= grid.nx || j >= grid.ny || k >= grid.nz) return false;
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3i hi(i, j, k);
      hi[a] += 1;
      if (field.open[a][field.faceIndex(a, i, j, k)] > 0.0 || field.open[a][field.faceIndex(a, hi.x(), hi.y(), hi.z())] > 0.0)
        return true;
    }
    return false;
  };
  int besideFluid = 0, interior = 0;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = field.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const size_t f = field.faceIndex(a, i, j, k);
          ASSERT_FALSE(std::isnan(field.solidVelocity[a][f]));
          if (field.open[a][f] > 0.0) continue;
          Eigen::Vector3i low(i, j, k);
          low[a] -= 1;
          if (cellOpen(i, j, k) || cellOpen(low.x(), low.y(), low.z())) {
            ASSERT_EQ(field.solidVelocity[a][f], solidVelocityAt(surface, field.face(a, i, j, k).centre)[a]);
            ++besideFluid;
          } else {
            ASSERT_EQ(field.solidVelocity[a][f], surface.meanVertexVelocity[a]);
            ++interior;
          }
        }
  }
  std::printf("covered faces beside fluid %d, interior %d\n", besideFluid, interior);
  EXPECT_GT(besideFluid, 100);
  EXPECT_GT(interior, 100);
}

// A deformable as the fluids see it, a rigid body: the centre of mass's velocity and the
// angular momentum over the inertia, exact for a rigid motion of its nodes.
TEST(DeformableInFluid, ADeformablesRigidMotionIsItsMomentaOverItsMassAndInertia) {
  const Array<double> x = {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 3.0}, mass = {1.0, 2.0, 3.0, 4.0};
  const Vec3 velocity(0.3, -1.0, 2.0), spin(0.5, -0.2, 0.7);
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < 4; ++i) centre += mass[i] * Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]) / 10.0;
  Array<double> v(12);
  for (int i = 0; i < 4; ++i) {
    const Vec3 vi = velocity + spin.cross(Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - centre);
    for (int k = 0; k < 3; ++k) v[3 * i + k] = vi[k];
  }
  const SolidMotion m = FluidImmersion::rigidMotion(x, v, mass);
  EXPECT_LT((m.velocity - velocity).norm(), 1e-12);
  EXPECT_LT((m.spin - spin).norm(), 1e-12);
}

// A fluid step's load holds the fluid's reaction to the change of the solids' motion since
// the step before began, over its own dt, whatever the steps of the bodies in between (a
// frame budget's pacing makes a fluid step span several of theirs); a solid the step before
// did not take has no change to react to.
TEST(DeformableInFluid, AStepSeesTheChangeOfASolidsMotionSinceTheStepBefore) {
  SolidMotionHistory history;
  const SolidMotion first{Vec3(0.0, 1.0, 0.0), Vec3(0.0, 0.0, 2.0)}, later{Vec3(0.0, 0.4, 0.0), Vec3(0.0, 0.0, 1.4)};
  const std::vector<SolidAcceleration> none = history.begin({{1, 1, first}}, 6.0 / 60.0);
  EXPECT_EQ(none[0].linear, Vec3::Zero());
  const double dt = 1.0 / 60.0;
  const std::vector<SolidAcceleration> seen = history.begin({{2, 1, first}, {1, 1, later}}, dt);
  EXPECT_EQ(seen[0].linear, Vec3::Zero());  // solid 2 is new
  EXPECT_NEAR(seen[1].linear.y(), (0.4 - 1.0) / dt, 1e-9);
  EXPECT_NEAR(seen[1].angular.z(), (1.4 - 2.0) / dt, 1e-9);
  EXPECT_EQ(history.begin({{1, 2, later}}, dt)[0].linear, Vec3::Zero());  // another generation: another solid
}

// The stabilization cancels at most the reaction the load shows: a load without it (the
// fluid's field far from a body that met a wall between two fluid steps) gets nothing added.
TEST(DeformableInFluid, TheStabilizationCancelsOnlyTheReactionTheLoadShows) {
  const Vec3 expected(0.0, 50.0, 0.0);
  EXPECT_EQ(shownReaction(expected, Vec3(3.0, -80.0, 0.0)), expected);
  EXPECT_EQ(shownReaction(expected, Vec3(0.0, -20.0, 7.0)), Vec3(0.0, 20.0, 0.0));
  EXPECT_EQ(shownReaction(expected, Vec3(0.0, 10.0, 0.0)), Vec3::Zero());
  EXPECT_EQ(shownReaction(Vec3::Zero(), Vec3(0.0, -10.0, 0.0)), Vec3::Zero());
}

// A load's viscous drag reaches the nodes off the colliders: its coefficient to be solved with
// their new velocities, its force at rest as a force. A drag of another surface's size, or
// with a negative coefficient (a push growing with the speed), is refused and changes nothing.
TEST(DeformableInFluid, TheViscousDragReachesTheFreeNodesAndABadOneIsRefused) {
  SurfaceMesh tet;
  tet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const Array<int32_t> vertexNode = {0, 1, 2, 3};
  const Array<double> x = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  FluidImmersion immersion;
  ASSERT_EQ(immersion.build(tet, vertexNode, x), Status::Ok) << lastError();
  const Array<Vec3> noForces(4, Vec3::Zero());
  VertexDrag drag{Array<Vec3>(4, Vec3(1.0, 2.0, 3.0)), Array<Vec3>(4, Vec3(0.5, 0.0, -0.5))};
  VertexDrag short3{Array<Vec3>(3, Vec3::Ones()), Array<Vec3>(3, Vec3::Zero())}, pushing = drag;
  pushing.coefficient[2].y() = -1.0;
  Array<uint8_t> touching(4, 0);
  touching[3] = 1;
  auto nodeDrag = [&](Array<double>* coefficient, Array<double>* force) {
    coefficient->assign(12, 0.0);
    force->assign(12, 0.0);
    immersion.addNodeDrag(touching, coefficient, force);
  };
  Array<double> coefficient, force;
  immersion.clearLoads();
  EXPECT_FALSE(immersion.addLoad(noForces, 0.0, SolidAcceleration{}, short3));
  EXPECT_FALSE(immersion.addLoad(noForces, 0.0, SolidAcceleration{}, pushing));
  EXPECT_FALSE(immersion.loaded());
  nodeDrag(&coefficient, &force);
  EXPECT_EQ(coefficient, Array<double>(12, 0.0));
  EXPECT_EQ(force, Array<double>(12, 0.0));

  EXPECT_TRUE(immersion.addLoad(noForces, 0.0, SolidAcceleration{}, drag));
  EXPECT_TRUE(immersion.addLoad(noForces, 0.0, SolidAcceleration{}, drag));  // a second fluid's
  nodeDrag(&coefficient, &force);
  for (int node = 0; node < 4; ++node)
    for (int k = 0; k < 3; ++k) {
      const bool free = node != 3;
      EXPECT_EQ(coefficient[3 * node + k], free ? 2.0 * drag.coefficient[node][k] : 0.0) << node << " " << k;
      EXPECT_EQ(force[3 * node + k], free ? 2.0 * drag.atRest[node][k] : 0.0) << node << " " << k;
    }
}

// Smoke flows around a deformable held still as around the rigid mesh of its surface.
TEST(DeformableInFluid, SmokeAroundAStillDeformableIsSmokeAroundTheSameRigidMesh) {
  auto run = [](bool deformable) {
    WorldConfig config;
    config.workerCount = 2;
    config.frameBudgetMs = 0.0;
    config.gravity = Vec3::Zero();
    std::unique_ptr<World> world;
    EXPECT_EQ(World::create(config, &world), Status::Ok);
    DeformableDesc jelly = jellyBlock(500.0, 0.3);
    if (deformable) {
      DeformableHandle h;
      EXPECT_EQ(world->createDeformable(jelly, &h), Status::Ok) << lastError();
      // Held still: the smoke's pressure would otherwise push it.
      DeformableBody& body = *world->deformable(h);
      std::vector<int32_t> all(static_cast<size_t>(body.nodeCount()));
      for (int32_t i = 0; i < body.nodeCount(); ++i) all[i] = i;
      EXPECT_EQ(body.setPinned(all.data(), body.nodeCount(), true), Status::Ok);
    } else {
      std::unique_ptr<DeformableBody> probe;  // for its surface, as the fluid would see it
      EXPECT_EQ(DeformableBody::create(jelly, &probe), Status::Ok);
      ColliderDesc c;
      c.bodyType = BodyType::Static;
      c.shape.type = ShapeType::TriangleMesh;
      const PreparedCollider& s = *probe->fluidSurface();
      c.shape.points.assign(s.shape.meshVertices.begin(), s.shape.meshVertices.end());
      for (const Eigen::Vector3i& t : s.shape.meshTriangles) c.shape.triangles.push_back({t[0], t[1], t[2]});
      ColliderHandle h;
      EXPECT_EQ(world->createCollider(c, &h), Status::Ok) << lastError();
    }
    FluidDesc smoke;
    smoke.kind = FluidKind::Smoke;
    smoke.grid.h = 1.0 / 20;
    smoke.grid.nx = smoke.grid.ny = smoke.grid.nz = 20;
    smoke.sides[3] = DomainSide::Open;
    FluidEmitter source;
    source.shape.type = FluidShape::Type::Sphere;
    source.shape.radius = 0.1;
    source.shape.centre = Vec3(0.5, 0.12, 0.5);
    source.velocity = Vec3(0.0, 1.0, 0.0);
    smoke.emitters.push_back(source);
    FluidHandle f;
    EXPECT_EQ(world->createFluid(smoke, &f), Status::Ok) << lastError();
    for (int s = 0; s < 30; ++s) EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok);
    return std::make_pair(Array<double>(world->fluid(f)->smokeDensity()), world->fluid(f)->fractions().open[1]);
  };
  const auto [smokeA, openA] = run(true);
  const auto [smokeB, openB] = run(false);
  ASSERT_EQ(openA.size(), openB.size());
  double worstOpen = 0.0, worstSmoke = 0.0, most = 0.0;
  for (size_t i = 0; i < openA.size(); ++i) worstOpen = std::max(worstOpen, std::abs(openA[i] - openB[i]));
  for (size_t i = 0; i < smokeA.size(); ++i) {
    worstSmoke = std::max(worstSmoke, std::abs(smokeA[i] - smokeB[i]));
    most = std::max(most, smokeB[i]);
  }
  EXPECT_LE(worstOpen, 1e-9);
  EXPECT_GT(most, 0.1);  // the smoke reached the block
  EXPECT_LE(worstSmoke, 1e-9 * most);
}

struct Immersion {
  double submerged = 0.0;        // mean over the last 2 s: fraction of the block's height below the surface
  double lastSecondSpeed = 0.0;  // the block's largest centre-of-mass speed over the last second
  double bottom = 0.0;           // the block's lowest node at the end
  double levelRise = 0.0;        // mean surface height at the end minus at the start
  double volume = 0.0;           // the block's volume (rest)
  double worstVolumeDrift = 0.0;  // of the liquid, relative
};

// A jelly block dropped with its bottom at the surface of a viscous liquid (see the rigid
// box's test in fluid_liquid_actor_test.cpp for why the viscosity is high) in a 1 m tank
// filled to 0.5 m, over a static ground just under the tank's floor (kGroundGap: a ground
// whose top lay on the floor would cover the floor's faces, and the liquid would count the
// bottom cells as partly solid and rise by a sixth of a cell).
constexpr double kGroundGap = 1e-3;

Immersion dropJelly(double density, int steps) {
  const int n = 24;
  const double h = 1.0 / n, fill = 0.5;
  Immersion out;
  FluidHandle fluid;
  std::unique_ptr<World> world = worldWithOpenTank(n, fill, 1e-6, &fluid, 0.05);
  if (!world) return out;
  ColliderDesc ground;
  ground.bodyType = BodyType::Static;
  ground.shape.type = ShapeType::Box;
  ground.shape.halfExtents = Vec3(2.0, 0.5, 2.0);
  ground.pose.position = Vec3(0.5, -0.5 - kGroundGap, 0.5);
  ColliderHandle groundHandle;
  EXPECT_EQ(world->createCollider(ground, &groundHandle), Status::Ok) << lastError();
  DeformableHandle jelly;
  EXPECT_EQ(world->createDeformable(jellyBlock(density, fill), &jelly), Status::Ok) << lastError();
  const DeformableBody& body = *world->deformable(jelly);
  out.volume = 0.3 * 0.2 * 0.3;  // at rest; the part in the tank is what displaces the liquid
  const double startLevel = meanSurfaceHeight(*world->fluid(fluid), Vec3(0.5, 0.0, 0.5), 0.15, 2 * h);
  const double startVolume = world->fluid(fluid)->liquidVolume();
  const int averaged = 120;
  double submergedSum = 0.0;
  for (int s = 0; s < steps; ++s) {
    EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok);
    const JellyMotion m = motionOf(body);
    const double level = meanSurfaceHeight(*world->fluid(fluid), m.centre, 0.15, 2 * h);
    if (s >= steps - averaged) submergedSum += std::clamp((level - m.bottom) / (m.top - m.bottom), 0.0, 1.0);
    if (s >= steps - 60) out.lastSecondSpeed = std::max(out.lastSecondSpeed, m.velocity.norm());
    out.worstVolumeDrift =
        std::max(out.worstVolumeDrift, std::abs(world->fluid(fluid)->liquidVolume() - startVolume) / startVolume);
    if (s == steps - 1) {
      out.bottom = m.bottom;
      out.levelRise = level - startLevel;
    }
  }
  out.submerged = submergedSum / averaged;
  return out;
}

// Half the liquid's density: it floats half submerged, and the viscous liquid brings it to rest.
TEST(DeformableInFluid, AHalfDensityJellyFloatsHalfSubmergedAndComesToRest) {
  const Immersion r = dropJelly(500.0, 480);
  std::printf("jelly of density 500: submerged fraction %.3f (mean of the last 2 s), speed over the last second "
              "<= %.3g m/s, liquid volume drift %.2e\n",
              r.submerged, r.lastSecondSpeed, r.worstVolumeDrift);
  EXPECT_NEAR(r.submerged, 0.5, 0.05);
  EXPECT_LT(r.lastSecondSpeed, 1e-2);
  EXPECT_LT(r.worstVolumeDrift, 0.01);
}

// Twice the liquid's density: it sinks to the floor and rests there, and the liquid's level
// rises by the block's volume over the tank's area.
TEST(DeformableInFluid, ATwiceDenseJellySinksToTheFloorRestsAndRaisesTheLevel) {
  const Immersion r = dropJelly(2000.0, 360);
  const double inTank = r.volume * (0.2 - std::max(0.0, -r.bottom)) / 0.2;
  const double expectedRise = inTank / (1.0 * 1.0);
  std::printf("jelly of density 2000: bottom at %.4f m, speed over the last second <= %.3g m/s, level rise %.4f m "
              "(volume / area %.4f m), liquid volume drift %.2e\n",
              r.bottom, r.lastSecondSpeed, r.levelRise, expectedRise, r.worstVolumeDrift);
  EXPECT_LT(r.bottom, 0.01);
  EXPECT_GT(r.bottom, -kGroundGap - 0.01);
  EXPECT_LT(r.lastSecondSpeed, 1e-2);
  EXPECT_NEAR(r.levelRise, expectedRise, 0.05 * expectedRise);
  EXPECT_LT(r.worstVolumeDrift, 0.01);
}

}  // namespace
}  // namespace vp

namespace vp {
namespace {

// The viscous traction is what the fluid's viscous step took from the surface: over one step
// the fluid's momentum grows by minus the impulse the surface takes (a block translating
// through still fluid, its walls 17 cells away, where the implicit step's spread is below
// round-off; the solve to 1e-12 so that its residual does not count).
TEST(DeformableInFluid, TheViscousTractionIsMinusWhatTheFluidsViscousStepTook) {
  const Vec3 velocity(0.3, -0.2, 0.1);
  MovingBlock block;
  fractionsOfMovingBlock([&](const Vec3&) { return velocity; }, &block);
  const double nu = 1e-3, dt = 1.0 / 60.0, density = 1000.0, h = block.grid.h;
  MacGrid grid;
  ViscosityWorkspace work;
  ASSERT_NO_FATAL_FAILURE(testutil::viscousStepFromRest(block.field, nu, dt, &grid, &work));
  Vec3 momentum = Vec3::Zero();
  for (int a = 0; a < 3; ++a)
    for (double u : grid.velocity[a]) momentum[a] += density * h * h * h * u;
  SurfacePressureLoad load;
  addViscousTraction(grid, work, density, dt, block.surface, &load);
  // On the vertices at the velocities the step saw; a drag, never a push.
  Vec3 vertexSum = Vec3::Zero();
  for (size_t v = 0; v < load.drag.coefficient.size(); ++v) {
    const Vec3& c = load.drag.coefficient[v];
    vertexSum += load.drag.atRest[v] - c.cwiseProduct(block.surface.vertexVelocities[v]);
    EXPECT_TRUE((c.array() >= 0.0).all()) << "vertex " << v;
  }
  std::printf("fluid momentum %.6g %.6g %.6g, surface impulse %.6g %.6g %.6g\n", momentum.x(), momentum.y(),
              momentum.z(), load.total.force.x() * dt, load.total.force.y() * dt, load.total.force.z() * dt);
  ASSERT_GT(momentum.norm(), 0.0);
  EXPECT_LT((momentum + load.total.force * dt).norm(), 1e-9 * momentum.norm());
  EXPECT_LT((vertexSum - load.total.force).norm(), 1e-12 * load.total.force.norm());
  // It drags the block back: against its motion.
  EXPECT_LT(load.total.force.dot(velocity), 0.0);
}

// A stiff jelly ball of `density` and `radius` in a still liquid of 24^3 cells, in zero
// gravity, spinning about the vertical at `spin` and moving along x at `speed`.
struct SpinningJelly {
  std::unique_ptr<World> world;
  DeformableBody* body = nullptr;
};

SpinningJelly spinningJelly(double kinematicViscosity, double density, double radius, double spin, double speed) {
  const Vec3 centre(0.5, 0.4, 0.5);
  SpinningJelly out;
  FluidHandle fluid;
  out.world = testutil::worldWithOpenTank(24, 0.85, 1e-8, &fluid, kinematicViscosity);
  if (!out.world) return out;
  EXPECT_EQ(out.world->setGravity(Vec3::Zero()), Status::Ok);
  SurfaceMesh sphere = test::icosphere(3, radius);
  for (Vec3& v : sphere.vertices) v += centre;
  DeformableDesc d;
  EXPECT_EQ(tetrahedralizeByStuffing(sphere, 6, &d.mesh), Status::Ok) << lastError();
  d.material.youngsModulus = 1e6;
  d.material.density = density;
  d.solver.tolerance = 1e-8;
  d.solver.maxIterations = 500;
  DeformableHandle ball;
  EXPECT_EQ(out.world->createDeformable(d, &ball), Status::Ok) << lastError();
  out.body = out.world->deformable(ball);
  if (out.body == nullptr) return out;
  const Array<double>& x = out.body->positions();
  Array<double> v(x.size());
  for (int32_t i = 0; i < out.body->nodeCount(); ++i) {
    const Vec3 xi(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    const Vec3 vi = speed * Vec3::UnitX() + spin * Vec3::UnitY().cross(xi - centre);
    for (int k = 0; k < 3; ++k) v[3 * i + k] = vi[k];
  }
  EXPECT_EQ(out.body->setVelocities(v.data(), static_cast<int64_t>(v.size())), Status::Ok);
  return out;
}

// A body's motion as a rigid body's: its spin about the vertical and its speed along x.
double spinAboutVertical(const DeformableBody& b) {
  return FluidImmersion::rigidMotion(b.positions(), b.velocities(), b.nodeMasses()).spin.y();
}
double speedAlongX(const DeformableBody& b) {
  return FluidImmersion::rigidMotion(b.positions(), b.velocities(), b.nodeMasses()).velocity.x();
}

// The spinning ball of the liquid's density and R = 0.2 m: the fraction of its spin left after
// `seconds`.
double spinLeft(double kinematicViscosity, double seconds) {
  const double spin = 3.0;
  SpinningJelly ball = spinningJelly(kinematicViscosity, 1000.0, 0.2, spin, 0.0);
  if (ball.body == nullptr) return 0.0;
  for (int s = 0; s < static_cast<int>(std::lround(seconds * 60.0)); ++s)
    EXPECT_EQ(ball.world->step(1.0 / 60.0), Status::Ok);
  return spinAboutVertical(*ball.body) / spin;
}

// Pressure cannot turn a ball (it acts along the normals, through the centre), so in an
// inviscid liquid the ball keeps its spin; in a viscous one the viscous traction spins it
// down. The leading-order rate for a ball started impulsively (Stokes' first problem on its
// surface, the boundary layer thinner than the ball): I dw/dt = -(8 pi / 3) mu w R^4 /
// sqrt(pi nu t), so w / w0 = exp(-10 (rho / rho_ball) sqrt(nu t / pi) / R). The steady part
// of the drag only adds to it. On this 24^3 grid the layer, sqrt(nu t) = 1.7 cells at the end,
// is not resolved and the no-slip condition sits a cell out (first order), which lowers the
// drag: the ball must lose at least half of the predicted share and not more than it.
TEST(DeformableInFluid, ViscousTractionSpinsDownABallThatPressureCannotTurn) {
  const double seconds = 0.5, nu = 0.01, radius = 0.2;
  const double inviscid = spinLeft(0.0, seconds), viscous = spinLeft(nu, seconds);
  const double predicted = std::exp(-10.0 * std::sqrt(nu * seconds / M_PI) / radius);
  std::printf("spin left after %.1f s: inviscid %.5f, nu = %g %.4f (leading order %.4f)\n", seconds, inviscid, nu,
              viscous, predicted);
  EXPECT_NEAR(inviscid, 1.0, 1e-3);
  EXPECT_GE(1.0 - viscous, 0.5 * (1.0 - predicted));
  EXPECT_LE(1.0 - viscous, 1.0 - predicted);
}

// A light jelly ball (density 200, R = 0.1 m) spinning at 3 rad/s and moving at 0.5 m/s in a
// liquid of nu = 0.05: the drag its faces couple is more than its mass can take explicitly over
// a step, and with the traction held explicitly the spin reversed twice before it stopped (the
// rigid ball's test in fluid_rigid_viscous_traction_test.cpp is its twin). Solved with the
// body's new velocities, the spin and the speed fall every frame, never past zero, to a tenth.
TEST(DeformableInFluid, ALightJellyInAThickLiquidSpinsAndSlowsDownWithoutOvershooting) {
  const double spin = 3.0, speed = 0.5;
  SpinningJelly ball = spinningJelly(0.05, 200.0, 0.1, spin, speed);
  ASSERT_NE(ball.body, nullptr);
  const testutil::SpinAndSpeed last = testutil::stepWhileSpinAndSpeedFall(*ball.world, 60, [&] {
    return testutil::SpinAndSpeed{spinAboutVertical(*ball.body), speedAlongX(*ball.body)};
  });
  ASSERT_GE(last.spin, 0.0);
  std::printf("light jelly in nu = 0.05 after 1 s: spin %.4f of its start, speed %.4f\n", last.spin / spin,
              last.speed / speed);
  EXPECT_LT(last.spin, 0.1 * spin);
  EXPECT_LT(last.speed, 0.1 * speed);
}

}  // namespace
}  // namespace vp
