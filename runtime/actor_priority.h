// Actor priorities: when the frame budget is short, actors of higher priority are served
// first. Deformables and fluids share one range so a host can rank them against each other.
#pragma once

#include "core/status.h"

namespace vp {

constexpr int kMinActorPriority = -1000000;
constexpr int kMaxActorPriority = 1000000;

// The message names the field "priority" and its value, as the defs do.
Status validateActorPriority(int priority);

}  // namespace vp
