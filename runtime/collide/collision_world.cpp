#include "collide/collision_world.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

#include "collide/collider.h"
#include "core/physical_limits.h"

namespace vp {

namespace {

// Bullet preallocates pools of contact manifolds and collision algorithms (4096 of each by
// default, about 4 MB per world, touched at creation) and falls back to the heap when one runs
// out. A world of a game scene uses tens to hundreds; smaller pools make a world cheap to
// create, which a host that makes one per level, or a test that makes thousands, notices.
btDefaultCollisionConstructionInfo poolSizes() {
  btDefaultCollisionConstructionInfo info;
  info.m_defaultMaxPersistentManifoldPoolSize = 256;
  info.m_defaultMaxCollisionAlgorithmPoolSize = 256;
  return info;
}

// The filter rule on the bits Bullet keeps in each proxy, and no static or kinematic pairs.
struct PairFilter : btOverlapFilterCallback {
  bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override {
    const auto* objectA = static_cast<const btCollisionObject*>(a->m_clientObject);
    const auto* objectB = static_cast<const btCollisionObject*>(b->m_clientObject);
    if (objectA->isStaticOrKinematicObject() && objectB->isStaticOrKinematicObject()) return false;
    const CollisionFilter filterA{static_cast<uint32_t>(a->m_collisionFilterGroup),
                                  static_cast<uint32_t>(a->m_collisionFilterMask)};
    const CollisionFilter filterB{static_cast<uint32_t>(b->m_collisionFilterGroup),
                                  static_cast<uint32_t>(b->m_collisionFilterMask)};
    return filterA.meets(filterB);
  }
};

}  // namespace

CollisionWorld::CollisionWorld(const Vec3& gravity)
    : configuration_(std::make_unique<btDefaultCollisionConfiguration>(poolSizes())),
      dispatcher_(std::make_unique<btCollisionDispatcher>(configuration_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<btSequentialImpulseConstraintSolver>()),
      world_(std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                       configuration_.get())),
      pairFilter_(std::make_unique<PairFilter>()) {
  world_->getPairCache()->setOverlapFilterCallback(pairFilter_.get());
  setGravity(gravity);
  // Bullet's solver shuffles constraints with a random seed only when this flag is set;
  // keep the default order so runs are reproducible.
  world_->getSolverInfo().m_solverMode &= ~SOLVER_RANDMIZE_ORDER;
}

CollisionWorld::~CollisionWorld() {
  // Colliders own their bodies; by now they are removed (World destroys them first).
}

void CollisionWorld::add(Collider& collider) {
  // Bullet keeps the bits as int; the cast keeps them as they are.
  world_->addRigidBody(collider.body(), static_cast<int>(collider.filter().category),
                       static_cast<int>(collider.filter().mask));
}

void CollisionWorld::setFilter(Collider& collider, const CollisionFilter& filter) {
  // Bodies asleep on it would stay asleep (hanging in the air) once it stops meeting them.
  btRigidBody* body = collider.body();
  btDispatcher* dispatcher = world_->getDispatcher();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    if (manifold->getBody0() != body && manifold->getBody1() != body) continue;
    const_cast<btCollisionObject*>(manifold->getBody0())->activate(true);
    const_cast<btCollisionObject*>(manifold->getBody1())->activate(true);
  }
  remove(collider);
  collider.setFilter(filter);
  add(collider);
}

void CollisionWorld::remove(Collider& collider) { world_->removeRigidBody(collider.body()); }

void CollisionWorld::setGravity(const Vec3& g) {
  world_->setGravity(btVector3(btScalar(g.x()), btScalar(g.y()), btScalar(g.z())));
}

struct CollisionWorld::BodyState {
  btRigidBody* body;
  btTransform transform;
  btVector3 linear, angular;
};

void CollisionWorld::saveDynamicBodies() {
  before_.clear();
  const btCollisionObjectArray& objects = world_->getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    btRigidBody* body = btRigidBody::upcast(objects[i]);
    if (body == nullptr || body->isStaticOrKinematicObject()) continue;
    before_.push_back(BodyState{body, body->getWorldTransform(), body->getLinearVelocity(), body->getAngularVelocity()});
  }
}

namespace {

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

bool diverged(const btRigidBody& body) {
  const btTransform& t = body.getWorldTransform();
  const btQuaternion q = t.getRotation();
  const btVector3& v = body.getLinearVelocity();
  const btVector3& w = body.getAngularVelocity();
  return !finite(t.getOrigin()) || !(std::isfinite(q.x()) && std::isfinite(q.y()) && std::isfinite(q.z()) &&
                                     std::isfinite(q.w())) ||
         !finite(v) || !finite(w) || !(v.length() <= kMaxSpeed) || !(w.length() <= kMaxAngularSpeed);
}

}  // namespace

int CollisionWorld::restoreDivergedBodies() {
  int restored = 0;
  for (const BodyState& s : before_) {
    if (!diverged(*s.body)) continue;
    s.body->setWorldTransform(s.transform);
    s.body->setInterpolationWorldTransform(s.transform);
    if (btMotionState* m = s.body->getMotionState()) m->setWorldTransform(s.transform);
    s.body->setLinearVelocity(s.linear);
    s.body->setAngularVelocity(s.angular);
    s.body->clearForces();
    s.body->updateInertiaTensor();
    // Bullet takes a body whose bounds overflowed out of the simulation (DISABLE_SIMULATION).
    s.body->forceActivationState(ACTIVE_TAG);
    s.body->activate(true);
    // Its contacts hold the diverged positions; the next step finds them anew.
    world_->getBroadphase()->getOverlappingPairCache()->cleanProxyFromPairs(s.body->getBroadphaseHandle(),
                                                                             dispatcher_.get());
    world_->updateSingleAabb(s.body);
    ++restored;
  }
  return restored;
}

CollisionWorld::StepResult CollisionWorld::step(double dt, double maxSubstep, Collider* const* kinematics, int count,
                                                Collider* const* loaded, int loadedCount) {
  saveDynamicBodies();
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt / maxSubstep - 1e-9)));
  const double h = dt / substeps;
  for (int k = 0; k < count; ++k) kinematics[k]->beginKinematicStep(dt);
  for (int s = 0; s < substeps; ++s) {
    for (int k = 0; k < count; ++k) kinematics[k]->advanceKinematic(h, s + 1 == substeps);
    for (int k = 0; k < loadedCount; ++k) loaded[k]->applyExternalLoads();
    // maxSubSteps = 0: one step of exactly h, no interpolation.
    world_->stepSimulation(btScalar(h), 0);
  }
  for (int k = 0; k < count; ++k) kinematics[k]->endKinematicStep();
  return StepResult{substeps, restoreDivergedBodies()};
}

}  // namespace vp
