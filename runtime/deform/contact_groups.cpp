#include "deform/contact_groups.h"

#include <numeric>

namespace vp {

std::vector<std::vector<int>> formContactGroups(const std::vector<int>& order,
                                                const std::vector<ContactGroupCandidate>& bodies,
                                                std::vector<PairContact>* pairs) {
  // Union–find over the bodies, each set named by its root.
  std::vector<int> parent(bodies.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int b) {
    while (parent[b] != b) b = parent[b] = parent[parent[b]];
    return b;
  };
  auto solvable = [&](int b) { return bodies[b].steps && bodies[b].onCpu; };
  for (PairContact& p : *pairs) {
    const int a = p.nodeBody, b = p.triangleBody;
    p.coupled = solvable(a) && solvable(b) && bodies[a].dt == bodies[b].dt;
    if (p.coupled) parent[root(a)] = root(b);
  }
  std::vector<std::vector<int>> groups;
  std::vector<int> groupOfRoot(bodies.size(), -1);
  for (int b : order) {
    int& g = groupOfRoot[root(b)];
    if (g < 0) {
      g = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[g].push_back(b);
  }
  return groups;
}

}  // namespace vp
