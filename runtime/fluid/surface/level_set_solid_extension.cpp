// Level set extension into solids (see level_set_solid_extension.h).
#include "fluid/surface/level_set_solid_extension.h"

#include <algorithm>
#include <limits>

#include "core/slab_passes.h"

namespace vp {

void extendLevelSetIntoSolids(const MacGridSpec& g, const Array<double>& cellWeights, Array<double>& phi,
                              Array<int64_t>& scratch) {
  SolidExtensionRun run;
  if (!ok(run.prepare(g, cellWeights, phi, scratch, std::numeric_limits<int64_t>::max()))) return;
  while (!run.advance()) {
  }
}

Status SolidExtensionRun::prepare(const MacGridSpec& grid, const Array<double>& cellWeights,
                                  Array<double>& phi, Array<int64_t>& scratch, int64_t samplesPerSlice) {
  pass_ = Pass::Done;
  const int64_t cells = static_cast<int64_t>(grid.nx) * grid.ny * grid.nz;
  if (cells <= 0 || static_cast<int64_t>(phi.size()) != cells || static_cast<int64_t>(cellWeights.size()) != cells)
    return fail(Status::InvalidArgument, "solid extension: grid (%d, %d, %d) with %zu values of phi, %zu weights",
                grid.nx, grid.ny, grid.nz, phi.size(), cellWeights.size());
  if (samplesPerSlice < 1)
    return fail(Status::InvalidArgument, "solid extension: samplesPerSlice = %lld must be >= 1",
                static_cast<long long>(samplesPerSlice));
  grid_ = grid;
  weights_ = &cellWeights;
  phi_ = &phi;
  unknown_ = &scratch;
  samplesPerSlice_ = samplesPerSlice;
  lastSliceSamples_ = 0;
  pass_ = Pass::Collect;
  position_ = 0;
  scratch.clear();
  pending_.resize(phi.size());
  return Status::Ok;
}

bool SolidExtensionRun::advance() {
  lastSliceSamples_ = runSamplesUpTo(
      samplesPerSlice_, [this] { return pass_ == Pass::Done; }, [this](int64_t left) { return step(left); });
  return pass_ == Pass::Done;
}

int64_t SolidExtensionRun::step(int64_t budget) {
  const MacGridSpec& g = grid_;
  Array<double>& phi = *phi_;
  Array<int64_t>& unknown = *unknown_;
  const int64_t passLength = pass_ == Pass::Collect ? static_cast<int64_t>(phi.size())
                             : pass_ == Pass::Scan  ? static_cast<int64_t>(unknown.size())
                                                    : static_cast<int64_t>(found_.size());
  const int64_t begin = position_, end = begin + std::min(budget, passLength - begin);
  position_ = end;
  switch (pass_) {
    case Pass::Collect:
      for (int64_t c = begin; c < end; ++c) {
        const bool solid = (*weights_)[static_cast<size_t>(c)] < kMaxCoveredCellWeight;
        pending_[static_cast<size_t>(c)] = solid ? 1 : 0;
        if (solid) unknown.push_back(c);
      }
      if (end < passLength) break;
      pass_ = unknown.empty() ? Pass::Done : Pass::Scan;
      position_ = 0;
      still_.clear();
      found_.clear();
      break;
    case Pass::Scan: {
      const int64_t sy = g.nx, sz = int64_t(g.nx) * g.ny;
      for (int64_t u = begin; u < end; ++u) {
        const int64_t c = unknown[static_cast<size_t>(u)];
        const int i = static_cast<int>(c % g.nx), j = static_cast<int>((c / g.nx) % g.ny), k = static_cast<int>(c / sz);
        double sum = 0.0;
        int n = 0;
        auto visit = [&](bool inside, int64_t nb) {
          if (inside && pending_[static_cast<size_t>(nb)] == 0) sum += phi[static_cast<size_t>(nb)], ++n;
        };
        visit(i > 0, c - 1);
        visit(i + 1 < g.nx, c + 1);
        visit(j > 0, c - sy);
        visit(j + 1 < g.ny, c + sy);
        visit(k > 0, c - sz);
        visit(k + 1 < g.nz, c + sz);
        if (n > 0) found_.emplace_back(c, sum / n);
        else still_.push_back(c);
      }
      if (end < passLength) break;
      // Enclosed by solids on every side: the cells left keep what they hold.
      pass_ = found_.empty() ? Pass::Done : Pass::Write;
      position_ = 0;
      break;
    }
    case Pass::Write:
      // A layer reads only earlier layers: values are written after the whole scan.
      for (int64_t f = begin; f < end; ++f) {
        const auto& [c, value] = found_[static_cast<size_t>(f)];
        phi[static_cast<size_t>(c)] = value;
        pending_[static_cast<size_t>(c)] = 0;
      }
      if (end < passLength) break;
      unknown.swap(still_);
      still_.clear();
      found_.clear();
      pass_ = unknown.empty() ? Pass::Done : Pass::Scan;
      position_ = 0;
      break;
    case Pass::Done:
      break;
  }
  return end - begin;
}

}  // namespace vp
