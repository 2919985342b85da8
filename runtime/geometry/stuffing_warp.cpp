#include "geometry/stuffing_warp.h"

#include "geometry/isosurface_stuffing.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vp {
namespace {

class Warp {
 public:
  Warp(const BccLattice& lattice, const std::vector<CutPoint>& cuts) : lattice_(lattice), cuts_(cuts) {
    for (size_t i = 0; i < cuts.size(); ++i) {
      at_[cuts[i].inside].push_back(static_cast<int32_t>(i));
      at_[cuts[i].outside].push_back(static_cast<int32_t>(i));
    }
  }

  // Rounds in id order: a violated vertex warps unless its nearest cut point's edge leads to
  // another violated vertex; a round that warps none warps the first waiting vertex.
  std::unordered_map<int64_t, int32_t> run() {
    std::vector<int64_t> pending;
    for (const auto& entry : at_) pending.push_back(entry.first);
    std::sort(pending.begin(), pending.end());
    while (!pending.empty()) {
      std::vector<int64_t> waiting;
      for (int64_t v : pending) {
        const int32_t cut = nearestViolated(v);
        if (cut < 0) continue;
        if (nearestViolated(otherEnd(cuts_[static_cast<size_t>(cut)], v)) >= 0) waiting.push_back(v);
        else warped_.emplace(v, cut);
      }
      if (waiting.size() == pending.size()) {
        warped_.emplace(waiting.front(), nearestViolated(waiting.front()));
        waiting.erase(waiting.begin());
      }
      pending.swap(waiting);
    }
    return std::move(warped_);
  }

 private:
  static int64_t otherEnd(const CutPoint& c, int64_t v) { return c.inside == v ? c.outside : c.inside; }

  // The nearest cut point that v violates on an edge whose other end is not warped; -1 if
  // none (or v is warped already).
  int32_t nearestViolated(int64_t v) const {
    if (warped_.count(v) != 0) return -1;
    const auto found = at_.find(v);
    if (found == at_.end()) return -1;
    double nearest = std::numeric_limits<double>::infinity();
    int32_t best = -1;
    for (int32_t i : found->second) {
      const CutPoint& c = cuts_[static_cast<size_t>(i)];
      if (warped_.count(otherEnd(c, v)) != 0) continue;
      const bool isLong = BccLattice::isLongEdge(lattice_.point(c.inside), lattice_.point(c.outside));
      const double fraction = c.inside == v ? c.t : 1.0 - c.t;
      const double length = isLong ? 1.0 : 0.5 * std::sqrt(3.0);
      if (fraction < (isLong ? kStuffingAlphaLong : kStuffingAlphaShort) && fraction * length < nearest) {
        nearest = fraction * length;
        best = i;
      }
    }
    return best;
  }

  const BccLattice& lattice_;
  const std::vector<CutPoint>& cuts_;
  std::unordered_map<int64_t, std::vector<int32_t>> at_;  // lattice vertex -> cut points on its edges
  std::unordered_map<int64_t, int32_t> warped_;
};

}  // namespace

std::unordered_map<int64_t, int32_t> warpLattice(const BccLattice& lattice, const std::vector<CutPoint>& cuts) {
  return Warp(lattice, cuts).run();
}

}  // namespace vp
