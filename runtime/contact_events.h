// Begin and end of touching between deformables and colliders, from the node contacts each
// deformable step leaves (DeformableBody::contacts, after lift-off releases, and
// DeformableBody::rigidContacts, its springs against dynamic bodies that pushed). A pair touches
// while at least one of the deformable's nodes is in contact with the collider. The events are
// those of the last world step; a deformable that did not step this frame (its rate lowered by
// the frame budget) changes nothing. Destroying a deformable drops its pairs without events.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math_types.h"

namespace vp {

class DeformableBody;

struct ContactEvent {
  enum class Type { Begin, End } type = Type::Begin;
  uint32_t deformableIndex1 = 0, deformableGeneration = 0;
  uint32_t colliderIndex1 = 0, colliderGeneration = 0;
  int32_t nodeCount = 0;          // Begin: nodes touching; End: 0
  Vec3 point = Vec3::Zero();      // Begin: the mean position of the touching nodes
  Vec3 normal = Vec3::Zero();     // Begin: their mean contact normal, out of the collider
};

class ContactEventTracker {
 public:
  void beginFrame() { events_.clear(); }
  // A deformable stepped: its contacts now against the pairs it had.
  void update(uint32_t index1, uint32_t generation, const DeformableBody& body);
  void forget(uint32_t index1, uint32_t generation);
  const std::vector<ContactEvent>& events() const { return events_; }
  // The pairs touching now, four ids each (deformable index1, generation, collider index1,
  // generation), for a saved world state; restoreState clears the events.
  std::vector<uint32_t> saveState() const;
  void restoreState(const std::vector<uint32_t>& pairs);

 private:
  struct Pair {
    uint32_t deformableIndex1, deformableGeneration, colliderIndex1, colliderGeneration;
    bool operator<(const Pair& o) const;
    bool operator==(const Pair& o) const;
  };
  std::vector<Pair> touching_;  // sorted
  std::vector<ContactEvent> events_;
};

}  // namespace vp
