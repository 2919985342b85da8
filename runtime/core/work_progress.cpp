#include "core/work_progress.h"

#include <algorithm>

namespace vp {

void WorkProgress::expectParts(int parts) {
  parts_ = std::max(parts, 1);
  head_ = done_;
  if (perPart_ > 0) expected_ = head_ + perPart_ * parts_;
}

void WorkProgress::finish(int parts) {
  parts_ = std::max(parts, 1);
  last_ = done_;
  const int64_t lastPerPart = (last_ - head_) / parts_;
  perPart_ = std::max(lastPerPart, lastPerPart + (perPart_ - lastPerPart) * 3 / 4);
  // The next piece is expected alike until its parts are known; at least this one's total
  // (the per-part figure is rounded down).
  expected_ = std::max(last_, head_ + perPart_ * parts_);
}

double WorkProgress::fraction() const {
  return static_cast<double>(done_) / static_cast<double>(std::max(expected_, done_ + 1));
}

bool WorkProgress::valid() const {
  return done_ >= 0 && last_ >= 0 && expected_ >= 0 && perPart_ >= 0 && parts_ >= 1 && head_ >= 0 &&
         head_ <= std::max(done_, last_);
}

}  // namespace vp
