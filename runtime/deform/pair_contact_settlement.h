// Equal and opposite, one step late: after the deformables of a frame have stepped, what the
// two sides of each pair contact applied beyond equal and opposite (pairContactMismatch) goes
// back, half to the node and half to the triangle's point, as impulses in their next steps.
// The correction is small (each side's spring saw the other side's velocity at the frame's
// start), so handing it back late does not feed the contact's dynamics, and the bodies'
// total momentum is kept.
#pragma once

#include <vector>

#include "deform/deformable_body.h"
#include "deform/pair_contacts.h"

namespace vp {

// bodies[b] is pair contacts' body b; steppedDt[b] the step it took this frame (0: none).
void settlePairContacts(const std::vector<PairContact>& pairs, const std::vector<DeformableBody*>& bodies,
                        const std::vector<double>& steppedDt);

}  // namespace vp
