// Saved world states (World::saveState / restoreState): stepping after a restore is bitwise
// the stepping after the save, for rigid stacks (Bullet's contact caches), deformables,
// fluids (a step in progress at the save included) and the default scene under a budget with
// a tick clock; into the same world and into a fresh one built from the same scene.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <algorithm>
#include <memory>
#include <vector>

#include "../budget/tick_clock.h"
#include "scene/scene_loader.h"
#include "snapshot/state_stream.h"
#include "world.h"

namespace vp {
namespace {

constexpr double kDt = 1.0 / 60.0;

// Everything a host can read that the steps change, as doubles.
std::vector<double> observe(World& world) {
  std::vector<double> out;
  for (ColliderHandle h : world.colliderHandles()) {
    const Collider& c = *world.collider(h);
    const Pose p = c.pose();
    const Vec3 v = c.linearVelocity(), w = c.angularVelocity();
    out.insert(out.end(), {p.position.x(), p.position.y(), p.position.z(), p.rotation.x(), p.rotation.y(),
                           p.rotation.z(), p.rotation.w(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z(),
                           double(c.sleeping())});
  }
  for (DeformableHandle h : world.deformableHandles()) {
    const DeformableBody& d = *world.deformable(h);
    out.insert(out.end(), d.positions().begin(), d.positions().end());
    out.insert(out.end(), d.velocities().begin(), d.velocities().end());
    out.push_back(double(d.contacts().size()));
  }
  for (FluidHandle h : world.fluidHandles()) {
    const FluidActor& f = *world.fluid(h);
    for (int a = 0; a < 3; ++a) out.insert(out.end(), f.grid().velocity[a].begin(), f.grid().velocity[a].end());
    for (const Array<double>* field : {&f.smokeDensity(), &f.temperature(), &f.levelSet(), &f.pressure()})
      out.insert(out.end(), field->begin(), field->end());
    out.push_back(double(f.stepCount()));
  }
  return out;
}

bool bitwiseEqual(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

struct SceneWorld {
  testutil::TickClock clock;
  std::unique_ptr<World> world;
  SceneWorld(const char* scene, double budgetMs) {
    WorldConfig config;
    config.clock = clock.clock();
    EXPECT_EQ(World::create(config, &world), Status::Ok);
    EXPECT_EQ(loadScene(*world, scene), Status::Ok) << lastError();
    EXPECT_EQ(world->setFrameBudget(budgetMs), Status::Ok);
  }
  std::vector<std::vector<double>> run(int steps) {
    std::vector<std::vector<double>> frames;
    for (int i = 0; i < steps; ++i) {
      const Status s = world->step(kDt);
      EXPECT_TRUE(s == Status::Ok || s == Status::PhaseFailed) << lastError();
      frames.push_back(observe(*world));
    }
    return frames;
  }
  bool fluidStepInProgress() const {
    for (FluidHandle h : world->fluidHandles())
      if (world->fluid(h)->stepInProgress()) return true;
    return false;
  }
};

// Steps `before`, saves (at the first frame from there on with a fluid step in progress, if
// one comes within `before` more frames), steps `after` frames; then restores and steps them
// again, in the same world and in a fresh one from the same scene.
void checkRoundTrip(const char* scene, double budgetMs, int before, int after, bool saveMidStep = false) {
  SceneWorld original(scene, budgetMs);
  original.run(before);
  for (int i = 0; i < before && !original.fluidStepInProgress(); ++i) original.run(1);
  EXPECT_EQ(original.fluidStepInProgress(), saveMidStep);
  std::vector<uint8_t> state;
  ASSERT_EQ(original.world->saveState(&state), Status::Ok) << lastError();
  EXPECT_FALSE(original.fluidStepInProgress());
  const double clockAtSave = original.clock.seconds;
  const std::vector<double> atSave = observe(*original.world);
  const std::vector<std::vector<double>> first = original.run(after);
  EXPECT_FALSE(bitwiseEqual(first.back(), atSave)) << "nothing moved: the test would prove nothing";

  ASSERT_EQ(original.world->restoreState(state.data(), state.size()), Status::Ok) << lastError();
  EXPECT_TRUE(bitwiseEqual(observe(*original.world), atSave));
  original.clock.seconds = clockAtSave;
  const std::vector<std::vector<double>> again = original.run(after);

  SceneWorld fresh(scene, budgetMs);
  ASSERT_EQ(fresh.world->restoreState(state.data(), state.size()), Status::Ok) << lastError();
  fresh.clock.seconds = clockAtSave;
  const std::vector<std::vector<double>> elsewhere = fresh.run(after);
  for (int i = 0; i < after; ++i) {
    ASSERT_TRUE(bitwiseEqual(first[i], again[i])) << scene << ": same world, frame " << i << " after the restore";
    ASSERT_TRUE(bitwiseEqual(first[i], elsewhere[i])) << scene << ": fresh world, frame " << i << " after the restore";
  }
}

TEST(WorldState, RigidStackContinuesBitwise) { checkRoundTrip(VP_TEST_DATA_DIR "/scenes/stack.json", 0.0, 90, 60); }

TEST(WorldState, DeformablesContinueBitwise) {
  checkRoundTrip(VP_TEST_DATA_DIR "/scenes/jelly_bridge.json", 0.0, 30, 30);
}

// Two jellies touching (deform/pair_contacts.h), the top one sliding: the contacts' friction
// states and the impulses their settlement left for the next steps are in the state.
TEST(WorldState, TouchingDeformablesContinueBitwise) {
  checkRoundTrip(VP_TEST_DATA_DIR "/scenes/jelly_stack.json", 0.0, 30, 30);
}

// A dynamic box sliding on a jelly, the two solved as one (deform/contact_group_solve.h): the
// friction states of the jelly's nodes on the box, and of the box's corners on the jelly's
// triangles (which the jelly keeps; there are some at the save), are in the state.
TEST(WorldState, AJellyAndTheDynamicBoxOnItContinueBitwise) {
  SceneWorld scene(VP_TEST_DATA_DIR "/scenes/box_on_jelly.json", 0.0);
  scene.run(20);
  EXPECT_GT(scene.world->deformable(scene.world->deformableHandles().front())->saveState().cornerFriction.size(), 0u);
  checkRoundTrip(VP_TEST_DATA_DIR "/scenes/box_on_jelly.json", 0.0, 20, 30);
}

TEST(WorldState, FluidsContinueBitwise) { checkRoundTrip(VP_TEST_DATA_DIR "/scenes/fluid_pair.json", 0.0, 20, 20); }

// A jelly and a rigid ball falling into a viscous liquid: the loads they took from the liquid's
// last step, the viscous drags included (fluid/solids/surface_pressure_load.h,
// collide/solid_motion.h), are in the state.
TEST(WorldState, BodiesInAViscousLiquidContinueBitwise) {
  checkRoundTrip(VP_TEST_DATA_DIR "/scenes/jelly_in_viscous_tank.json", 0.0, 20, 20);
}

// A negative viscous drag coefficient (a push that grows with the speed) cannot come from a
// fluid's step; a buffer holding one, under a valid checksum, is refused and changes nothing.
void expectANegatedDragRefused(World& world, double coefficient, const char* message) {
  ASSERT_GT(coefficient, 0.0) << "no drag in the load: the test would prove nothing";
  std::vector<uint8_t> state;
  ASSERT_EQ(world.saveState(&state), Status::Ok) << lastError();
  std::vector<uint8_t> bad = state;
  size_t found = 0;
  for (size_t at = kStateHeaderBytes; at + sizeof coefficient <= bad.size(); ++at)
    if (std::memcmp(bad.data() + at, &coefficient, sizeof coefficient) == 0) {
      const double negative = -coefficient;
      std::memcpy(bad.data() + at, &negative, sizeof negative);
      ++found;
    }
  ASSERT_GT(found, 0u);
  const uint64_t sum = stateChecksum(bad.data() + kStateHeaderBytes, bad.size() - kStateHeaderBytes);
  std::memcpy(bad.data() + kStateChecksumOffset, &sum, sizeof sum);
  EXPECT_EQ(world.restoreState(bad.data(), bad.size()), Status::ParseError);
  EXPECT_NE(std::string(lastError()).find(message), std::string::npos) << lastError();
  std::vector<uint8_t> after;
  ASSERT_EQ(world.saveState(&after), Status::Ok) << lastError();
  EXPECT_EQ(after, state);
}

TEST(WorldState, ANegativeViscousDragIsRefused) {
  SceneWorld scene(VP_TEST_DATA_DIR "/scenes/jelly_in_viscous_tank.json", 0.0);
  scene.run(20);
  const FluidActor& tank = *scene.world->fluid(scene.world->fluidHandles().front());
  ASSERT_EQ(tank.loads().size(), 2u);
  double onVertex = 0.0, onBody = 0.0;
  for (const FluidColliderLoad& l : tank.loads()) {
    for (const Vec3& c : l.drag.coefficient) onVertex = std::max(onVertex, c.maxCoeff());
    onBody = std::max(onBody, l.rigidDrag.linear.maxCoeff());
  }
  expectANegatedDragRefused(*scene.world, onVertex, "vertex drag is out of range");
  expectANegatedDragRefused(*scene.world, onBody, "rigid drag is out of range");
}

// Under a budget (tick clock: deterministic) fluid steps span frames; the save lands on one
// (at frame 50 or the first after it with a fluid step in progress), then 50 frames more.
TEST(WorldState, DefaultSceneUnderABudgetContinuesBitwise) {
  checkRoundTrip(VP_TEST_DATA_DIR "/../../sample_host/scenes/default.json", 16.0, 50, 50, true);
}

TEST(WorldState, SavingTwiceGivesTheSameBuffer) {
  SceneWorld w(VP_TEST_DATA_DIR "/scenes/stack.json", 0.0);
  w.run(60);
  std::vector<uint8_t> a, b;
  ASSERT_EQ(w.world->saveState(&a), Status::Ok);
  ASSERT_EQ(w.world->saveState(&b), Status::Ok);
  EXPECT_EQ(a, b);
}

// The frame plan's state of each actor travels with it: a deformable paced by a liquid
// (FramePlan::Pacing::WithLiquids) must not take the liquid's completed steps for new ones
// after a restore, nor forget that a blown-up step gave it back its own rate for a while.
TEST(WorldState, TheFramePlansStateOfADeformableIsInTheState) {
  SceneWorld w(VP_TEST_DATA_DIR "/../../sample_host/scenes/default.json", 16.0);
  w.run(20);
  const DeformableHandle duck = w.world->deformableHandles().front();
  ActorSchedule& s = w.world->deformable(duck)->schedule();
  s.liquidSteps = 12345;
  s.ownRateFrames = 7;
  s.calmFrames = 3;
  const ActorSchedule saved = s;
  std::vector<uint8_t> state;
  ASSERT_EQ(w.world->saveState(&state), Status::Ok) << lastError();
  SceneWorld fresh(VP_TEST_DATA_DIR "/../../sample_host/scenes/default.json", 16.0);
  ASSERT_EQ(fresh.world->restoreState(state.data(), state.size()), Status::Ok) << lastError();
  const ActorSchedule& restored = fresh.world->deformable(duck)->schedule();
  EXPECT_EQ(restored.liquidSteps, saved.liquidSteps);
  EXPECT_EQ(restored.ownRateFrames, saved.ownRateFrames);
  EXPECT_EQ(restored.calmFrames, saved.calmFrames);
  EXPECT_EQ(restored.interval, saved.interval);
  EXPECT_EQ(restored.waitedFrames, saved.waitedFrames);
}

// The rebuild a save does keeps Bullet's contact points (its warm start): a resting stack's
// manifolds are the same after the save as before it.
TEST(WorldState, SavingKeepsBulletsContactPoints) {
  SceneWorld w(VP_TEST_DATA_DIR "/scenes/stack.json", 0.0);
  w.run(90);
  std::vector<Collider*> colliders;
  for (ColliderHandle h : w.world->colliderHandles()) colliders.push_back(w.world->collider(h));
  const std::vector<CollisionWorld::SavedManifold> before = w.world->collisionWorld().saveContacts(colliders);
  ASSERT_GE(before.size(), 3u);
  std::vector<uint8_t> state;
  ASSERT_EQ(w.world->saveState(&state), Status::Ok);
  const std::vector<CollisionWorld::SavedManifold> after = w.world->collisionWorld().saveContacts(colliders);
  ASSERT_EQ(after.size(), before.size());
  EXPECT_EQ(std::memcmp(after.data(), before.data(), before.size() * sizeof(before[0])), 0);
  double impulse = 0.0;
  for (const CollisionWorld::SavedManifold& m : after)
    for (int p = 0; p < m.pointCount; ++p) impulse += m.points[p].appliedImpulse;
  EXPECT_GT(impulse, 0.0);  // the warm start is there to keep
}

}  // namespace
}  // namespace vp
