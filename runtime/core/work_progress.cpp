#include "core/work_progress.h"

#include <algorithm>

namespace vp {

void WorkProgress::finish() {
  last_ = done_;
  expected_ = std::max(last_, last_ + (expected_ - last_) * 3 / 4);
}

double WorkProgress::fraction() const {
  return static_cast<double>(done_) / static_cast<double>(std::max(expected_, done_ + 1));
}

}  // namespace vp
