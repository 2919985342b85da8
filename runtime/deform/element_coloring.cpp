#include "deform/element_coloring.h"

#include <cstdint>

namespace vp {

Status colorElements(int32_t nodeCount, const int32_t* elementNodes, int64_t elementCount, int nodesPerElement,
                     ElementColoring* out) {
  // One bit per colour per node; 4 words allow 256 colours, far above what tet meshes need
  // (a node's elements bound the colours a new element must avoid).
  constexpr int kWords = 4;
  std::vector<uint64_t> used(static_cast<size_t>(nodeCount) * kWords, 0);
  std::vector<int16_t> color(static_cast<size_t>(elementCount));
  int colors = 0;
  for (int64_t e = 0; e < elementCount; ++e) {
    uint64_t taken[kWords] = {0, 0, 0, 0};
    for (int a = 0; a < nodesPerElement; ++a) {
      const uint64_t* u = &used[static_cast<size_t>(elementNodes[e * nodesPerElement + a]) * kWords];
      for (int w = 0; w < kWords; ++w) taken[w] |= u[w];
    }
    int c = -1;
    for (int w = 0; w < kWords && c < 0; ++w)
      if (~taken[w]) c = w * 64 + __builtin_ctzll(~taken[w]);
    if (c < 0)
      return fail(Status::Unsupported, "element %lld needs more than %d colours (node valence too high)",
                  static_cast<long long>(e), 64 * kWords);
    color[e] = static_cast<int16_t>(c);
    colors = c + 1 > colors ? c + 1 : colors;
    for (int a = 0; a < nodesPerElement; ++a)
      used[static_cast<size_t>(elementNodes[e * nodesPerElement + a]) * kWords + c / 64] |= uint64_t(1) << (c % 64);
  }
  out->colorStart.assign(static_cast<size_t>(colors) + 1, 0);
  for (int16_t c : color) out->colorStart[c + 1]++;
  for (int c = 0; c < colors; ++c) out->colorStart[c + 1] += out->colorStart[c];
  out->order.resize(static_cast<size_t>(elementCount));
  std::vector<int32_t> fill(out->colorStart.begin(), out->colorStart.end() - 1);
  for (int64_t e = 0; e < elementCount; ++e) out->order[fill[color[e]]++] = static_cast<int32_t>(e);
  return Status::Ok;
}

}  // namespace vp
