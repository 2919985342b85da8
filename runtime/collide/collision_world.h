// The Bullet world behind a VolPhys world: owns Bullet's pipeline objects and steps rigid
// bodies in fixed-size sub-steps (no interpolation, so what the host reads is the simulated
// state, and fluids/deformables see the same poses Bullet used).
#pragma once

#include <memory>

#include "core/math_types.h"

class btDefaultCollisionConfiguration;
class btCollisionDispatcher;
class btBroadphaseInterface;
class btSequentialImpulseConstraintSolver;
class btDiscreteDynamicsWorld;

namespace vp {

class Collider;

class CollisionWorld {
 public:
  explicit CollisionWorld(const Vec3& gravity);
  ~CollisionWorld();
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;

  void add(Collider& collider);
  void remove(Collider& collider);
  void setGravity(const Vec3& gravity);

  // Steps by dt in ceil(dt / maxSubstep) equal sub-steps; returns the sub-step count.
  // `kinematics` lists the kinematic colliders to drive (count entries); `loaded` the
  // dynamic ones carrying a fluid load (loadedCount entries), applied on every sub-step.
  int step(double dt, double maxSubstep, Collider* const* kinematics, int count, Collider* const* loaded = nullptr,
           int loadedCount = 0);

  btDiscreteDynamicsWorld& bullet() { return *world_; }

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
};

}  // namespace vp
