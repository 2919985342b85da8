// The Bullet world behind a VolPhys world: owns Bullet's pipeline objects and steps rigid
// bodies in fixed-size sub-steps (no interpolation, so what the host reads is the simulated
// state, and fluids/deformables see the same poses Bullet used).
#pragma once

#include <memory>
#include <vector>

#include "core/collision_filter.h"
#include "core/math_types.h"

class btDefaultCollisionConfiguration;
class btCollisionDispatcher;
class btBroadphaseInterface;
class btSequentialImpulseConstraintSolver;
class btDiscreteDynamicsWorld;
struct btOverlapFilterCallback;

namespace vp {

class Collider;

class CollisionWorld {
 public:
  explicit CollisionWorld(const Vec3& gravity);
  ~CollisionWorld();
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;

  // Bullet sees the collider's CollisionFilter; pairs of which neither body is dynamic are
  // never tested (as Bullet's default filter does).
  void add(Collider& collider);
  void remove(Collider& collider);
  // A new filter takes effect from the next step: the body is taken out and put back, so the
  // broadphase forgets its old pairs and finds the ones the new bits allow.
  void setFilter(Collider& collider, const CollisionFilter& filter);
  void setGravity(const Vec3& gravity);

  struct StepResult {
    int substeps = 0;
    int restoredBodies = 0;  // dynamic bodies the divergence guard put back
  };
  // Steps by dt in ceil(dt / maxSubstep) equal sub-steps. `kinematics` lists the kinematic
  // colliders to drive (count entries); `loaded` the dynamic ones carrying a fluid or host load
  // (loadedCount entries), applied on every sub-step.
  // Divergence guard: a dynamic body whose pose or velocity comes out of the step not finite,
  // or faster than kMaxSpeed (kMaxAngularSpeed turning; core/physical_limits.h, the limits a
  // host may set), goes back to its pose and velocity before the step, its contacts dropped.
  StepResult step(double dt, double maxSubstep, Collider* const* kinematics, int count,
                  Collider* const* loaded = nullptr, int loadedCount = 0);

  btDiscreteDynamicsWorld& bullet() { return *world_; }

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::unique_ptr<btOverlapFilterCallback> pairFilter_;
  struct BodyState;
  std::vector<BodyState> before_;  // the dynamic bodies at the start of the step
  void saveDynamicBodies();
  int restoreDivergedBodies();
};

}  // namespace vp
