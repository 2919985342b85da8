#include "fluid/solids/solid_motion_history.h"

#include <algorithm>

namespace vp {

std::vector<SolidAcceleration> SolidMotionHistory::begin(const std::vector<Entry>& now, double dt) {
  std::vector<SolidAcceleration> seen(now.size());
  for (size_t i = 0; i < now.size() && dt > 0.0; ++i) {
    const auto before = std::find_if(last_.begin(), last_.end(), [&](const Entry& e) {
      return e.index1 == now[i].index1 && e.generation == now[i].generation;
    });
    if (before == last_.end()) continue;
    seen[i].linear = (now[i].motion.velocity - before->motion.velocity) / dt;
    seen[i].angular = (now[i].motion.spin - before->motion.spin) / dt;
  }
  last_ = now;
  return seen;
}

}  // namespace vp
