#include "collide/collision_world.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

#include "collide/collider.h"

namespace vp {

CollisionWorld::CollisionWorld(const Vec3& gravity)
    : configuration_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<btCollisionDispatcher>(configuration_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<btSequentialImpulseConstraintSolver>()),
      world_(std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                       configuration_.get())) {
  setGravity(gravity);
  // Bullet's solver shuffles constraints with a random seed only when this flag is set;
  // keep the default order so runs are reproducible.
  world_->getSolverInfo().m_solverMode &= ~SOLVER_RANDMIZE_ORDER;
}

CollisionWorld::~CollisionWorld() {
  // Colliders own their bodies; by now they are removed (World destroys them first).
}

void CollisionWorld::add(Collider& collider) { world_->addRigidBody(collider.body()); }

void CollisionWorld::remove(Collider& collider) { world_->removeRigidBody(collider.body()); }

void CollisionWorld::setGravity(const Vec3& g) {
  world_->setGravity(btVector3(btScalar(g.x()), btScalar(g.y()), btScalar(g.z())));
}

int CollisionWorld::step(double dt, double maxSubstep, Collider* const* kinematics, int count,
                         Collider* const* loaded, int loadedCount) {
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt / maxSubstep - 1e-9)));
  const double h = dt / substeps;
  for (int k = 0; k < count; ++k) kinematics[k]->beginKinematicStep(dt);
  for (int s = 0; s < substeps; ++s) {
    for (int k = 0; k < count; ++k) kinematics[k]->advanceKinematic(h, s + 1 == substeps);
    for (int k = 0; k < loadedCount; ++k) loaded[k]->applyFluidLoad();
    // maxSubSteps = 0: one step of exactly h, no interpolation.
    world_->stepSimulation(btScalar(h), 0);
  }
  for (int k = 0; k < count; ++k) kinematics[k]->endKinematicStep();
  return substeps;
}

}  // namespace vp
