// Writing and reading each actor's saved state (actor_states.h) in the format of
// state_stream.h. A read checks what it reads against the actor it is for (sizes, ranges,
// finite values) and fills the state only; nothing is applied until the whole buffer has
// been read.
#pragma once

#include "snapshot/actor_states.h"
#include "snapshot/state_stream.h"

namespace vp {

class DeformableBody;
class FluidActor;

void writeColliderState(StateWriter& out, const ColliderState& s);
void readColliderState(StateReader& in, bool hasGeometry, ColliderState* s);

void writeDeformableState(StateWriter& out, const DeformableState& s);
void readDeformableState(StateReader& in, const DeformableBody& body, DeformableState* s);

void writeFluidState(StateWriter& out, const FluidState& s);
void readFluidState(StateReader& in, const FluidActor& fluid, FluidState* s);

}  // namespace vp
