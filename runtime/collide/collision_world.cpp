#include "collide/collision_world.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>
#include <utility>

#include "collide/bullet_doubles.h"
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

int CollisionWorld::restoreDivergedBodies(bool all) {
  int restored = 0;
  for (const BodyState& s : before_) {
    if (!all && !diverged(*s.body)) continue;
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
  energy_.begin(*world_);
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt / maxSubstep - 1e-9)));
  const double h = dt / substeps;
  for (int k = 0; k < count; ++k) kinematics[k]->beginKinematicStep(dt);
  for (int s = 0; s < substeps; ++s) {
    for (int k = 0; k < count; ++k) kinematics[k]->advanceKinematic(h, s + 1 == substeps);
    for (int k = 0; k < loadedCount; ++k) loaded[k]->applyExternalLoads();
    energy_.beforeSubstep();
    // maxSubSteps = 0: one step of exactly h, no interpolation.
    world_->stepSimulation(btScalar(h), 0);
    energy_.afterSubstep(*world_, h);
  }
  for (int k = 0; k < count; ++k) kinematics[k]->endKinematicStep();
  StepResult result{substeps, restoreDivergedBodies(false), energy_.finish()};
  // The bodies' energy is one account (their contacts pass it between them): a step that
  // gains more than its work explains is undone for all of them. Not judged when a body
  // diverged already: its energy has no meaning.
  if (result.restoredBodies == 0 && StepEnergyGuard::blewUp(result.energy, energy_.totalMass())) {
    result.energyBlewUp = true;
    result.restoredBodies = restoreDivergedBodies(true);
  }
  return result;
}


static_assert(CollisionWorld::kMaxManifoldPoints == MANIFOLD_CACHE_SIZE);

namespace {

using SavedContactPoint = CollisionWorld::SavedContactPoint;

SavedContactPoint savePoint(const btManifoldPoint& p) {
  SavedContactPoint s{};
  toDoubles(p.m_localPointA, s.localA);
  toDoubles(p.m_localPointB, s.localB);
  toDoubles(p.m_positionWorldOnA, s.worldA);
  toDoubles(p.m_positionWorldOnB, s.worldB);
  toDoubles(p.m_normalWorldOnB, s.normalOnB);
  toDoubles(p.m_lateralFrictionDir1, s.lateralDir1);
  toDoubles(p.m_lateralFrictionDir2, s.lateralDir2);
  s.distance = p.m_distance1;
  s.friction = p.m_combinedFriction;
  s.rollingFriction = p.m_combinedRollingFriction;
  s.spinningFriction = p.m_combinedSpinningFriction;
  s.restitution = p.m_combinedRestitution;
  s.appliedImpulse = p.m_appliedImpulse;
  s.previousRhs = p.m_prevRHS;
  s.lateralImpulse1 = p.m_appliedImpulseLateral1;
  s.lateralImpulse2 = p.m_appliedImpulseLateral2;
  s.contactMotion1 = p.m_contactMotion1;
  s.contactMotion2 = p.m_contactMotion2;
  s.cfm = p.m_contactCFM;
  s.erp = p.m_contactERP;
  s.frictionCfm = p.m_frictionCFM;
  s.partId0 = p.m_partId0;
  s.partId1 = p.m_partId1;
  s.index0 = p.m_index0;
  s.index1 = p.m_index1;
  s.flags = p.m_contactPointFlags;
  s.lifeTime = p.m_lifeTime;
  return s;
}

btManifoldPoint loadPoint(const SavedContactPoint& s) {
  btManifoldPoint p;
  p.m_localPointA = btVectorFrom(s.localA);
  p.m_localPointB = btVectorFrom(s.localB);
  p.m_positionWorldOnA = btVectorFrom(s.worldA);
  p.m_positionWorldOnB = btVectorFrom(s.worldB);
  p.m_normalWorldOnB = btVectorFrom(s.normalOnB);
  p.m_lateralFrictionDir1 = btVectorFrom(s.lateralDir1);
  p.m_lateralFrictionDir2 = btVectorFrom(s.lateralDir2);
  p.m_distance1 = btScalar(s.distance);
  p.m_combinedFriction = btScalar(s.friction);
  p.m_combinedRollingFriction = btScalar(s.rollingFriction);
  p.m_combinedSpinningFriction = btScalar(s.spinningFriction);
  p.m_combinedRestitution = btScalar(s.restitution);
  p.m_appliedImpulse = btScalar(s.appliedImpulse);
  p.m_prevRHS = btScalar(s.previousRhs);
  p.m_appliedImpulseLateral1 = btScalar(s.lateralImpulse1);
  p.m_appliedImpulseLateral2 = btScalar(s.lateralImpulse2);
  p.m_contactMotion1 = btScalar(s.contactMotion1);
  p.m_contactMotion2 = btScalar(s.contactMotion2);
  p.m_contactCFM = btScalar(s.cfm);
  p.m_contactERP = btScalar(s.erp);
  p.m_frictionCFM = btScalar(s.frictionCfm);
  p.m_partId0 = s.partId0;
  p.m_partId1 = s.partId1;
  p.m_index0 = s.index0;
  p.m_index1 = s.index1;
  p.m_contactPointFlags = s.flags;
  p.m_lifeTime = s.lifeTime;
  p.m_userPersistentData = nullptr;
  return p;
}

// The same contact seen from the other body: A and B trade places, the normal on B turns
// round, and the friction impulses (along directions the solver derives from the relative
// velocity, which turns round too) change sign.
SavedContactPoint swapped(const SavedContactPoint& p) {
  SavedContactPoint s = p;
  std::copy(p.localB, p.localB + 3, s.localA);
  std::copy(p.localA, p.localA + 3, s.localB);
  std::copy(p.worldB, p.worldB + 3, s.worldA);
  std::copy(p.worldA, p.worldA + 3, s.worldB);
  for (int k = 0; k < 3; ++k) s.normalOnB[k] = -p.normalOnB[k];
  s.lateralImpulse1 = -p.lateralImpulse1;
  s.lateralImpulse2 = -p.lateralImpulse2;
  std::swap(s.partId0, s.partId1);
  std::swap(s.index0, s.index1);
  return s;
}

}  // namespace

std::vector<CollisionWorld::SavedManifold> CollisionWorld::saveContacts(const std::vector<Collider*>& colliders) const {
  std::unordered_map<const btCollisionObject*, uint32_t> place;
  for (size_t i = 0; i < colliders.size(); ++i) place[colliders[i]->body()] = static_cast<uint32_t>(i);
  std::vector<SavedManifold> out;
  const btDispatcher* dispatcher = dispatcher_.get();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = const_cast<btDispatcher*>(dispatcher)->getManifoldByIndexInternal(m);
    const int points = std::min(manifold->getNumContacts(), kMaxManifoldPoints);
    const auto a = place.find(manifold->getBody0()), b = place.find(manifold->getBody1());
    if (points == 0 || a == place.end() || b == place.end()) continue;
    SavedManifold saved{};  // the points past pointCount zero too: a state's bytes are all set
    const bool swap = a->second > b->second;
    saved.body0 = swap ? b->second : a->second;
    saved.body1 = swap ? a->second : b->second;
    saved.pointCount = points;
    for (int p = 0; p < points; ++p) {
      const SavedContactPoint point = savePoint(manifold->getContactPoint(p));
      saved.points[p] = swap ? swapped(point) : point;
    }
    out.push_back(saved);
  }
  std::stable_sort(out.begin(), out.end(), [](const SavedManifold& x, const SavedManifold& y) {
    return x.body0 != y.body0 ? x.body0 < y.body0 : x.body1 < y.body1;
  });
  return out;
}

void CollisionWorld::rebuild(const std::vector<Collider*>& colliders, const std::vector<ColliderState>& states,
                             const std::vector<SavedManifold>& contacts) {
  for (Collider* c : colliders) remove(*c);
  auto broadphase = std::make_unique<btDbvtBroadphase>();
  broadphase->getOverlappingPairCache()->setOverlapFilterCallback(pairFilter_.get());
  world_->setBroadphase(broadphase.get());
  broadphase_ = std::move(broadphase);
  // A body enters the broadphase with the box of its pose then (the tree depends on it), and
  // adding it sets some of its state (a static one is put to sleep): the state goes on before
  // and again after.
  for (size_t i = 0; i < colliders.size(); ++i) {
    colliders[i]->restoreState(states[i]);
    add(*colliders[i]);
    colliders[i]->restoreState(states[i]);
  }
  // Bullet makes no manifold for a pair of which neither body is awake; a body asleep on
  // another keeps its contacts, so every body is awake for this pass.
  for (Collider* c : colliders) c->body()->forceActivationState(ACTIVE_TAG);
  world_->performDiscreteCollisionDetection();
  for (size_t i = 0; i < colliders.size(); ++i) {
    colliders[i]->body()->forceActivationState(states[i].body.activationState);
    colliders[i]->body()->setDeactivationTime(btScalar(states[i].body.deactivationTime));
  }
  // The pass's manifolds by body pair (lower address first), emptied for the saved points.
  using BodyPair = std::pair<const btCollisionObject*, const btCollisionObject*>;
  auto pairOf = [](const btCollisionObject* a, const btCollisionObject* b) {
    return a < b ? BodyPair(a, b) : BodyPair(b, a);
  };
  std::map<BodyPair, std::vector<btPersistentManifold*>> unfilled;
  for (int m = dispatcher_->getNumManifolds(); m-- > 0;) {
    btPersistentManifold* manifold = dispatcher_->getManifoldByIndexInternal(m);
    manifold->clearManifold();
    unfilled[pairOf(manifold->getBody0(), manifold->getBody1())].push_back(manifold);  // last first
  }
  for (const SavedManifold& saved : contacts) {
    const btCollisionObject* a = colliders[saved.body0]->body();
    const auto found = unfilled.find(pairOf(a, colliders[saved.body1]->body()));
    if (found == unfilled.end() || found->second.empty()) continue;  // the pair no longer meets
    btPersistentManifold* manifold = found->second.back();  // in the dispatcher's order
    found->second.pop_back();
    const bool swap = manifold->getBody0() != a;
    for (int p = 0; p < saved.pointCount; ++p)
      manifold->getContactPoint(p) = loadPoint(swap ? swapped(saved.points[p]) : saved.points[p]);
    manifold->setNumContacts(saved.pointCount);
  }
}

}  // namespace vp
