#include "deform/pair_contact_settlement.h"

#include "deform/pair_contact_terms.h"

namespace vp {

void settlePairContacts(const std::vector<PairContact>& pairs, const std::vector<DeformableBody*>& bodies,
                        const std::vector<double>& steppedDt) {
  for (const PairContact& p : pairs) {
    // Equal and opposite by construction; a rigid side is always coupled (contact_groups.h).
    if (p.coupled || p.rigidSide || p.rigidNode) continue;
    DeformableBody& nodeBody = *bodies[p.nodeBody];
    DeformableBody& triangleBody = *bodies[p.triangleBody];
    const Vec3 excess = pairContactMismatch(p, steppedDt[p.nodeBody], nodeBody.velocities(),
                                            steppedDt[p.triangleBody], triangleBody.velocities());
    nodeBody.addContactImpulse(p.node, -0.5 * excess);
    for (int i = 0; i < 3; ++i) triangleBody.addContactImpulse(p.triangleNodes[i], -0.5 * p.weights[i] * excess);
  }
}

}  // namespace vp
