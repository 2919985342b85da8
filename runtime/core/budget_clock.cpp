#include "core/budget_clock.h"

#include <algorithm>
#include <chrono>

namespace vp {

double Clock::seconds() const {
  if (now) return now(context);
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

Deadline::Deadline(const Clock& clock, double budgetMs) : clock_(clock), start_(clock.seconds()) {
  end_ = budgetMs > 0.0 ? start_ + budgetMs * 1e-3 : std::numeric_limits<double>::infinity();
}

bool Deadline::expired() const { return !unlimited() && clock_.seconds() >= end_; }

double Deadline::remainingMs() const {
  if (unlimited()) return std::numeric_limits<double>::infinity();
  return std::max(0.0, (end_ - clock_.seconds()) * 1e3);
}

double Deadline::elapsedMs() const { return (clock_.seconds() - start_) * 1e3; }

Deadline Deadline::share(double fraction) const {
  return shareLeaving(fraction, 0.0, std::numeric_limits<double>::infinity());
}

Deadline Deadline::shareLeaving(double fraction, double reserveMs, double laterMs) const {
  return unlimited() ? *this : shareLeaving(fraction, reserveMs, laterMs, clock_.seconds());
}

Deadline Deadline::shareLeaving(double fraction, double reserveMs, double laterMs, double now) const {
  Deadline d = *this;
  if (unlimited()) return d;
  const double available = std::max(0.0, end_ - now - std::max(reserveMs, 0.0) * 1e-3);
  d.start_ = now;
  d.end_ = now + std::max(available * std::clamp(fraction, 0.0, 1.0), available - std::max(laterMs, 0.0) * 1e-3);
  return d;
}

Deadline Deadline::within(double ms) const {
  Deadline d = *this;
  const double now = clock_.seconds();
  d.start_ = now;
  d.end_ = std::min(end_, now + std::max(ms, 0.0) * 1e-3);
  return d;
}

}  // namespace vp
