#include "collide/rigid_step_energy.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>

namespace vp {

namespace {

double kineticEnergy(const btRigidBody& b) {
  const double m = 1.0 / b.getInvMass();
  const btVector3& v = b.getLinearVelocity();
  // ½ ωᵀ I ω in the body's principal frame; a locked axis (inverse inertia 0) cannot turn.
  const btVector3 w = b.getWorldTransform().getBasis().transpose() * b.getAngularVelocity();
  const btVector3& inverseInertia = b.getInvInertiaDiagLocal();
  double e = 0.5 * m * double(v.length2());
  for (int a = 0; a < 3; ++a)
    if (inverseInertia[a] > 0) e += 0.5 * double(w[a]) * double(w[a]) / double(inverseInertia[a]);
  return e;
}

const btRigidBody* kinematicBody(const btCollisionObject* o) {
  const btRigidBody* b = btRigidBody::upcast(o);
  return b != nullptr && b->isKinematicObject() ? b : nullptr;
}

// The most a sub-step's contacts with moving bodies and its penetration recovery put in.
double contactWorkBound(btDiscreteDynamicsWorld& world, double h) {
  const btContactSolverInfo& info = world.getSolverInfo();
  btDispatcher& dispatcher = *world.getDispatcher();
  double bound = 0.0;
  for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
    const btPersistentManifold& m = *dispatcher.getManifoldByIndexInternal(i);
    const btRigidBody* moving = kinematicBody(m.getBody0());
    if (moving == nullptr) moving = kinematicBody(m.getBody1());
    for (int k = 0; k < m.getNumContacts(); ++k) {
      const btManifoldPoint& p = m.getContactPoint(k);
      if (moving != nullptr) {
        const btVector3 impulse = p.m_normalWorldOnB * p.m_appliedImpulse +
                                  p.m_lateralFrictionDir1 * p.m_appliedImpulseLateral1 +
                                  p.m_lateralFrictionDir2 * p.m_appliedImpulseLateral2;
        const btVector3 at = p.getPositionWorldOnB() - moving->getCenterOfMassPosition();
        bound += double(impulse.length()) * double(moving->getVelocityInLocalPoint(at).length());
      }
      // A deep penetration is undone by moving positions (split impulse): no speed gained.
      const double depth = -double(p.getDistance()) - double(info.m_linearSlop);
      if (!(depth > 0.0) || (info.m_splitImpulse && -depth <= info.m_splitImpulsePenetrationThreshold)) continue;
      bound += std::abs(double(p.m_appliedImpulse)) * info.m_erp2 * depth / h;
    }
  }
  return bound;
}

void copy(const btVector3& from, double* to) {
  for (int a = 0; a < 3; ++a) to[a] = from[a];
}

}  // namespace

void RigidStepEnergy::begin(btDiscreteDynamicsWorld& world) {
  bodies_.clear();
  energy_ = StepEnergy{};
  totalMass_ = 0.0;
  const btCollisionObjectArray& objects = world.getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    btRigidBody* b = btRigidBody::upcast(objects[i]);
    if (b == nullptr || b->isStaticOrKinematicObject() || !(b->getInvMass() > 0)) continue;
    bodies_.push_back(Body{b, {}, {}});
    energy_.kineticStart += kineticEnergy(*b);
    totalMass_ += 1.0 / b->getInvMass();
  }
}

void RigidStepEnergy::beforeSubstep() {
  for (Body& b : bodies_) {
    copy(b.body->getTotalForce(), b.force);  // Bullet adds gravity inside its step
    copy(b.body->getTotalTorque(), b.torque);
  }
}

void RigidStepEnergy::afterSubstep(btDiscreteDynamicsWorld& world, double h) {
  for (const Body& b : bodies_) {
    const btVector3& v = b.body->getLinearVelocity();
    const btVector3& w = b.body->getAngularVelocity();
    const btVector3& g = b.body->getGravity();
    const double m = 1.0 / double(b.body->getInvMass());
    for (int a = 0; a < 3; ++a) {
      energy_.gravityWork += m * double(g[a]) * double(v[a]) * h;
      energy_.appliedWork += (b.force[a] * double(v[a]) + b.torque[a] * double(w[a])) * h;
    }
  }
  energy_.boundedWork += contactWorkBound(world, h);
}

StepEnergy RigidStepEnergy::finish() const {
  StepEnergy e = energy_;
  for (const Body& b : bodies_) e.kineticEnd += kineticEnergy(*b.body);
  return e;
}

}  // namespace vp
