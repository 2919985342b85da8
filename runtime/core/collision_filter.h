// Collision filtering (Box2D's rule): every collider, deformable and fluid has a category (the
// bits it belongs to) and a mask (the bits it meets). Two of them meet when each one's category
// is in the other's mask. Bullet applies it to rigid pairs, a deformable's contacts to the
// colliders it touches, a fluid's face fractions (and its loads) to the colliders it sees.
#pragma once

#include <cstdint>

namespace vp {

struct CollisionFilter {
  // Everything meets everything by default.
  uint32_t category = 1;
  uint32_t mask = 0xFFFFFFFFu;

  bool meets(const CollisionFilter& other) const {
    return (category & other.mask) != 0 && (other.category & mask) != 0;
  }
};

}  // namespace vp
