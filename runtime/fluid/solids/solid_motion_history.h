// What a fluid's steps saw of its dynamic solids' motion. A step's pressure holds the fluid's
// reaction to the change of each solid's motion since the step before, -addedMass x
// (change / the step's dt): the fluid near the solid took the solid's old velocity then and
// must take the new one now. The bodies' stabilization for added mass (collide/collider.cpp,
// deform/fluid_immersion.h) takes that reaction out of the load and solves it implicitly, so
// it needs the change this step saw, which is not the body's change over its own last step
// once a fluid step spans several of the body's (a frame budget's pacing): the body's last
// step then holds accelerations the load does not (a contact's), and the load is held over
// several body steps.
#pragma once

#include <cstdint>
#include <vector>

#include "collide/solid_motion.h"

namespace vp {

class SolidMotionHistory {
 public:
  struct Entry {
    uint32_t index1 = 0, generation = 0;  // the solid (FluidCollider's identity)
    SolidMotion motion;
  };

  // At the start of a step of length dt taking the solids `now`: for each, the change of its
  // motion since the last step's start over dt (zero for one the last step did not take,
  // or for a step of no length); then `now` becomes the last step's.
  std::vector<SolidAcceleration> begin(const std::vector<Entry>& now, double dt);

  // The motions the last step started with (a saved state), and back.
  const std::vector<Entry>& lastStep() const { return last_; }
  void restore(std::vector<Entry> lastStep) { last_ = std::move(lastStep); }

 private:
  std::vector<Entry> last_;
};

}  // namespace vp
