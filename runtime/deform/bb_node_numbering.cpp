#include "deform/bb_node_numbering.h"

#include <map>

#include "deform/bb_element_matrices.h"
#include "deform/bb_multi_index.h"

namespace vp {

Status numberBBNodes(const TetMesh& mesh, int degree, BBNodeNumbering* out) {
  const int64_t elements = static_cast<int64_t>(mesh.tets.size());
  const int N = bbNodeCount(degree);
  BBNodeNumbering n;
  n.restPositions.assign(mesh.vertices.begin(), mesh.vertices.end());
  n.support.assign(n.restPositions.size(), {-1, -1, -1});
  n.elementNodes.resize(static_cast<size_t>(N * elements));
  // A std::map keyed by the whole key: the numbering must not depend on hashing, and meshes
  // are numbered once, at creation.
  std::map<std::array<int32_t, 10>, int32_t> nodeOfKey;
  for (int64_t e = 0; e < elements; ++e) {
    double corners[12], nodePositions[3 * kBBMaxNodes];
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) corners[3 * a + k] = mesh.vertices[mesh.tets[e][a]][k];
    if (degree > 1) VP_TRY(bbRestNodePositions(degree, corners, nodePositions));
    for (int a = 0; a < N; ++a) {
      if (a < 4) {
        n.elementNodes[N * e + a] = mesh.tets[e][a];
        continue;
      }
      BBNodeKey key;
      VP_TRY(bbNodeKey(degree, a, mesh.tets[e].data(), &key));
      const std::array<int32_t, 10> id{key.count, key.vertices[0], key.vertices[1], key.vertices[2], key.vertices[3],
                                       key.exponents[0], key.exponents[1], key.exponents[2], key.exponents[3],
                                       key.slot};
      auto [it, inserted] = nodeOfKey.emplace(id, static_cast<int32_t>(n.restPositions.size()));
      if (inserted) {
        n.restPositions.emplace_back(nodePositions[3 * a], nodePositions[3 * a + 1], nodePositions[3 * a + 2]);
        n.support.push_back({key.vertices[0], key.vertices[1], key.count > 2 ? key.vertices[2] : -1});
      }
      n.elementNodes[N * e + a] = it->second;
    }
  }
  n.nodeCount = static_cast<int32_t>(n.restPositions.size());
  *out = std::move(n);
  return Status::Ok;
}

}  // namespace vp
