// Which deformables solve their step together this frame (deform/contact_group_solve.h).
//
// Two bodies join when a pair contact touches both and both can share a solve: each steps
// this frame, over the same dt, on the CPU. Their contacts are then coupled (PairContact::
// coupled); a contact between bodies that cannot share a solve stays a one-step-late spring
// on each side (pair_contacts.h). A body's contacts with itself are coupled whenever it steps
// on the CPU: it is one system anyway. Dynamic rigid bodies are candidates too (after the
// deformables, as pair bodies are numbered): two deformables touching one body join its group.
#pragma once

#include <vector>

#include "deform/pair_contacts.h"

namespace vp {

struct ContactGroupCandidate {
  bool steps = false;     // due this frame
  bool onCpu = true;      // its solve runs on the CPU
  double dt = 0.0;        // the step it takes
};

// bodies[b] is pair contacts' body b; `order` the bodies that step, in the order they are
// served. Marks the coupled contacts and returns the groups, each a list of bodies in `order`'s
// order, the groups ordered by their first member; every body of `order` is in one group.
std::vector<std::vector<int>> formContactGroups(const std::vector<int>& order,
                                                const std::vector<ContactGroupCandidate>& bodies,
                                                std::vector<PairContact>* pairs);

}  // namespace vp
