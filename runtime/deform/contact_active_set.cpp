#include "deform/contact_active_set.h"

#include <algorithm>

namespace vp {
namespace {

Vec3 nodeVelocity(const Array<double>& v, int32_t i) { return Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]); }

void setNodeVelocity(Array<double>* v, int32_t i, const Vec3& value) {
  for (int k = 0; k < 3; ++k) (*v)[3 * i + k] = value[k];
}

// A contact's prescribed velocity: `base` with its normal part replaced by the landing speed.
Vec3 prescribedVelocity(const Vec3& base, const NodeContact& c) {
  return base + (c.normalSpeed - base.dot(c.normal)) * c.normal;
}

}  // namespace

Vec3 tangentialSlip(const Vec3& velocity, const NodeContact& contact) {
  Vec3 slip = velocity - contact.colliderVelocity;
  slip -= slip.dot(contact.normal) * contact.normal;
  return slip;
}

void ContactActiveSet::resize(int32_t nodeCount) {
  sliding_.assign(static_cast<size_t>(nodeCount), 0);
  lastNormalImpulse_.assign(static_cast<size_t>(nodeCount), 0.0);
}

void ContactActiveSet::begin(const Array<double>& x, const Array<double>& v, const Array<double>& motion,
                             const Array<int32_t>& surfaceNodes, const std::vector<ContactCollider>& colliders,
                             double h, double friction, double margin, NodeConstraints* held, Array<double>* vNext) {
  findNodeContacts(x, motion, surfaceNodes, colliders, h, friction, margin, &contacts_);
  contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(),
                                 [&](const NodeContact& c) { return held->kind[c.node] == NodeConstraints::kFixed; }),
                  contacts_.end());
  friction_.clear();
  for (const NodeContact& c : contacts_) {
    const int32_t i = c.node;
    const Vec3 vi = nodeVelocity(v, i);
    const Vec3 slip = tangentialSlip(vi, c);
    const bool slides = sliding_[i] && slip.norm() > kSlipSpeed && lastNormalImpulse_[i] > 0.0;
    held->kind[i] = slides ? NodeConstraints::kContact : NodeConstraints::kFixed;
    for (int k = 0; k < 3; ++k) held->normal[3 * i + k] = c.normal[k];
    setNodeVelocity(vNext, i, prescribedVelocity(slides ? vi : c.colliderVelocity, c));
    friction_.push_back(slides ? Vec3(-c.friction * lastNormalImpulse_[i] * slip.normalized()) : Vec3::Zero());
  }
}

void ContactActiveSet::addFriction(Array<double>* rhs) const {
  for (size_t c = 0; c < contacts_.size(); ++c)
    for (int k = 0; k < 3; ++k) (*rhs)[3 * contacts_[c].node + k] += friction_[c][k];
}

bool ContactActiveSet::applyCoulomb(const Array<Vec3>& impulses, NodeConstraints* held, Array<double>* vNext,
                                    Array<double>* rhs) {
  bool changed = false;
  size_t kept = 0;
  for (size_t c = 0; c < contacts_.size(); ++c) {
    const NodeContact& contact = contacts_[c];
    const int32_t i = contact.node;
    Vec3& friction = friction_[c];
    auto setFriction = [&](const Vec3& f) {
      for (int k = 0; k < 3; ++k) (*rhs)[3 * i + k] += f[k] - friction[k];
      friction = f;
    };
    const double jn = impulses[c].dot(contact.normal);
    if (jn < 0.0) {
      setFriction(Vec3::Zero());
      held->kind[i] = NodeConstraints::kFree;
      changed = true;
      continue;
    }
    if (held->kind[i] == NodeConstraints::kFixed) {
      const Vec3 jt = impulses[c] - jn * contact.normal;
      if (jt.norm() > contact.friction * jn) {
        held->kind[i] = NodeConstraints::kContact;
        setFriction(contact.friction * jn * jt.normalized());
        changed = true;
      }
    } else if (tangentialSlip(nodeVelocity(*vNext, i), contact).dot(friction) > 0.0) {
      // Friction now pushes along the slip: it overshot.
      held->kind[i] = NodeConstraints::kFixed;
      setNodeVelocity(vNext, i, prescribedVelocity(contact.colliderVelocity, contact));
      setFriction(Vec3::Zero());
      changed = true;
    }
    lastNormalImpulse_[i] = jn;
    friction_[kept] = friction;
    contacts_[kept++] = contact;
  }
  contacts_.resize(kept);
  friction_.resize(kept);
  return changed;
}

void ContactActiveSet::rememberSliding(const Array<double>& vNext, const NodeConstraints& held) {
  std::fill(sliding_.begin(), sliding_.end(), 0);
  for (const NodeContact& c : contacts_) {
    if (held.kind[c.node] != NodeConstraints::kContact) continue;
    sliding_[c.node] = tangentialSlip(nodeVelocity(vNext, c.node), c).norm() > kSlipSpeed ? 1 : 0;
  }
}

void ContactActiveSet::saveTo(DeformableState* state) const {
  state->lastNormalImpulse = lastNormalImpulse_;
  state->sliding = sliding_;
  state->contacts = contacts_;
}

void ContactActiveSet::restoreFrom(DeformableState* state) {
  lastNormalImpulse_ = std::move(state->lastNormalImpulse);
  sliding_ = std::move(state->sliding);
  contacts_ = std::move(state->contacts);
}

}  // namespace vp
