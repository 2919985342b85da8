// The Bullet world behind a VolPhys world: owns Bullet's pipeline objects and steps rigid
// bodies in fixed-size sub-steps (no interpolation, so what the host reads is the simulated
// state, and fluids/deformables see the same poses Bullet used).
#pragma once

#include <memory>
#include <vector>

#include "collide/rigid_step_energy.h"
#include "core/collision_filter.h"
#include "core/math_types.h"
#include "snapshot/actor_states.h"

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
    StepEnergy energy;        // the dynamic bodies' (collide/rigid_step_energy.h)
    bool energyBlewUp = false;
  };
  // Steps by dt in ceil(dt / maxSubstep) equal sub-steps. `kinematics` lists the kinematic
  // colliders to drive (count entries); `loaded` the dynamic ones carrying a fluid or host load
  // (loadedCount entries), applied on every sub-step.
  // Divergence guard: a dynamic body whose pose or velocity comes out of the step not finite,
  // or faster than kMaxSpeed (kMaxAngularSpeed turning; core/physical_limits.h, the limits a
  // host may set), goes back to its pose and velocity before the step, its contacts dropped;
  // when the dynamic bodies' energy rose beyond what the step's work explains
  // (core/step_energy.h, collide/rigid_step_energy.h), all of them do.
  StepResult step(double dt, double maxSubstep, Collider* const* kinematics, int count,
                  Collider* const* loaded = nullptr, int loadedCount = 0);

  btDiscreteDynamicsWorld& bullet() { return *world_; }

  // Saved world states (vpWorldSaveState). One contact point Bullet keeps between steps (its
  // warm start), in Bullet's precision widened to double.
  struct SavedContactPoint {
    double localA[3], localB[3], worldA[3], worldB[3], normalOnB[3], lateralDir1[3], lateralDir2[3];
    double distance, friction, rollingFriction, spinningFriction, restitution, appliedImpulse, previousRhs;
    double lateralImpulse1, lateralImpulse2, contactMotion1, contactMotion2, cfm, erp, frictionCfm;
    int32_t partId0, partId1, index0, index1, flags, lifeTime;
  };
  static constexpr int kMaxManifoldPoints = 4;  // Bullet's MANIFOLD_CACHE_SIZE
  struct SavedManifold {
    uint32_t body0 = 0, body1 = 0;  // places in the collider list; body0 < body1
    int32_t pointCount = 0;
    int32_t unused = 0;  // no padding: a state's bytes are all written
    SavedContactPoint points[kMaxManifoldPoints];
  };
  // The manifolds with points, bodies numbered by their place in `colliders` (all of the
  // world's, in slot order), ordered by those numbers.
  std::vector<SavedManifold> saveContacts(const std::vector<Collider*>& colliders) const;
  // Bullet's caches rebuilt from `states` (one per collider, Collider::saveState's) and
  // `contacts` (their bodies' places in `colliders`, as a read checks): the bodies go back in the order of
  // `colliders` into a new broadphase with their states, one collision pass finds their
  // pairs, and each manifold gets its saved points (none if it has no saved ones). Bullet keeps history
  // of its own (the broadphase's tree and its pair list's order, which pairs linger) that no
  // state can hold; rebuilding it from the state alone is what makes a restored world step
  // exactly like the saved one, which is rebuilt the same way when it is saved.
  void rebuild(const std::vector<Collider*>& colliders, const std::vector<ColliderState>& states,
               const std::vector<SavedManifold>& contacts);

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
  RigidStepEnergy energy_;  // of the step running
  // Puts back the diverged dynamic bodies (`all`: every one); returns how many.
  int restoreDivergedBodies(bool all);
};

}  // namespace vp
