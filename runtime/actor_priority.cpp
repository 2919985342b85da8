#include "actor_priority.h"

namespace vp {

Status validateActorPriority(int priority) {
  if (priority < kMinActorPriority || priority > kMaxActorPriority)
    return fail(Status::InvalidArgument, "priority = %d: must be in [%d, %d]", priority, kMinActorPriority,
                kMaxActorPriority);
  return Status::Ok;
}

}  // namespace vp
