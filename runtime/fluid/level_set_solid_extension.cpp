// Level set extension into solids (see level_set_solid_extension.h).
#include "fluid/level_set_solid_extension.h"

#include <utility>

namespace vp {

void extendLevelSetIntoSolids(const MacGridSpec& g, const std::vector<double>& cellWeights, std::vector<double>& phi,
                              std::vector<int64_t>& unknown) {
  const int64_t sx = 1, sy = g.nx, sz = int64_t(g.nx) * g.ny;
  unknown.clear();
  for (int64_t c = 0; c < static_cast<int64_t>(phi.size()); ++c)
    if (cellWeights[static_cast<size_t>(c)] < 0.5) unknown.push_back(c);
  if (unknown.empty()) return;
  // -1 marks a cell still unknown; known cells hold 0 (this is cellWeights-sized scratch).
  std::vector<int8_t> pending(phi.size(), 0);
  for (int64_t c : unknown) pending[static_cast<size_t>(c)] = 1;
  std::vector<int64_t> still;
  std::vector<std::pair<int64_t, double>> found;
  while (!unknown.empty()) {
    found.clear();
    still.clear();
    for (int64_t c : unknown) {
      const int i = static_cast<int>(c % g.nx), j = static_cast<int>((c / g.nx) % g.ny), k = static_cast<int>(c / sz);
      double sum = 0.0;
      int n = 0;
      auto visit = [&](bool inside, int64_t nb) {
        if (inside && pending[static_cast<size_t>(nb)] == 0) sum += phi[static_cast<size_t>(nb)], ++n;
      };
      visit(i > 0, c - sx);
      visit(i + 1 < g.nx, c + sx);
      visit(j > 0, c - sy);
      visit(j + 1 < g.ny, c + sy);
      visit(k > 0, c - sz);
      visit(k + 1 < g.nz, c + sz);
      if (n > 0) found.emplace_back(c, sum / n);
      else still.push_back(c);
    }
    if (found.empty()) break;  // enclosed by solids on every side: keep what they hold
    // A layer reads only earlier layers: values are written after the scan.
    for (const auto& [c, value] : found) phi[static_cast<size_t>(c)] = value, pending[static_cast<size_t>(c)] = 0;
    unknown.swap(still);
  }
}

}  // namespace vp
