#include "deform/degree_hierarchy.h"

#include <algorithm>
#include <array>
#include <map>

#include "deform/bb_evaluation.h"
#include "deform/bb_multi_index.h"

namespace vp {
namespace {

// Dense local elevation matrix from degree `from` to degree `to` (to > from), row-major
// bbNodeCount(to) x bbNodeCount(from): composed single-step elevations.
void localElevation(int from, int to, Array<double>* matrix) {
  int rows = bbNodeCount(from);
  Array<double> current(static_cast<size_t>(rows * rows), 0.0);
  for (int k = 0; k < rows; ++k) current[k * rows + k] = 1.0;
  const int cols = bbNodeCount(from);
  for (int d = from; d < to; ++d) {
    BBElevationRow step[kBBMaxNodes];
    bbElevationRows(d, step);
    const int next = bbNodeCount(d + 1);
    Array<double> elevated(static_cast<size_t>(next * cols), 0.0);
    for (int r = 0; r < next; ++r)
      for (int m = 0; m < step[r].count; ++m)
        for (int c = 0; c < cols; ++c) elevated[r * cols + c] += step[r].weight[m] * current[step[r].node[m] * cols + c];
    current.swap(elevated);
    rows = next;
  }
  matrix->swap(current);
}

}  // namespace

Status buildDegreeHierarchy(const std::vector<int>& degrees, const int32_t* fineNodes, int64_t elementCount,
                            int32_t fineNodeCount, DegreeHierarchy* out) {
  if (degrees.empty() || degrees[0] < 1 || degrees[0] > kBBMaxDegree)
    return fail(Status::InvalidArgument, "degrees[0] = %d: expected the fine degree 1..%d",
                degrees.empty() ? 0 : degrees[0], kBBMaxDegree);
  for (size_t l = 1; l < degrees.size(); ++l)
    if (degrees[l] < 1 || degrees[l] >= degrees[l - 1])
      return fail(Status::InvalidArgument, "degrees[%zu] = %d: must be >= 1 and below degrees[%zu] = %d", l,
                  degrees[l], l - 1, degrees[l - 1]);
  DegreeHierarchy h;
  const int fineN = bbNodeCount(degrees[0]);
  int32_t vertexCount = 0;
  for (int64_t e = 0; e < elementCount; ++e)
    for (int a = 0; a < 4; ++a) vertexCount = std::max(vertexCount, fineNodes[fineN * e + a] + 1);
  {
    DegreeLevel fine;
    fine.degree = degrees[0];
    fine.nodeCount = fineNodeCount;
    fine.elementNodes.assign(fineNodes, fineNodes + fineN * elementCount);
    h.levels.push_back(std::move(fine));
  }
  for (size_t l = 1; l < degrees.size(); ++l) {
    DegreeLevel level;
    level.degree = degrees[l];
    const int N = bbNodeCount(level.degree);
    level.elementNodes.resize(static_cast<size_t>(N * elementCount));
    level.nodeCount = vertexCount;
    std::map<std::array<int32_t, 10>, int32_t> nodeOfKey;
    for (int64_t e = 0; e < elementCount; ++e) {
      const int32_t* corners = &fineNodes[fineN * e];
      for (int a = 0; a < N; ++a) {
        if (a < 4) {
          level.elementNodes[N * e + a] = corners[a];
          continue;
        }
        BBNodeKey key;
        VP_TRY(bbNodeKey(level.degree, a, corners, &key));
        const std::array<int32_t, 10> id{key.count, key.vertices[0], key.vertices[1], key.vertices[2],
                                         key.vertices[3], key.exponents[0], key.exponents[1], key.exponents[2],
                                         key.exponents[3], key.slot};
        auto [it, inserted] = nodeOfKey.emplace(id, level.nodeCount);
        if (inserted) ++level.nodeCount;
        level.elementNodes[N * e + a] = it->second;
      }
    }
    // Prolongation levels[l] -> levels[l - 1].
    const DegreeLevel& fine = h.levels[l - 1];
    const int Nf = bbNodeCount(fine.degree);
    Array<double> E;
    localElevation(level.degree, fine.degree, &E);
    NodeProlongation P;
    P.fineNodes = fine.nodeCount;
    P.coarseNodes = level.nodeCount;
    std::vector<std::vector<std::pair<int32_t, double>>> rows(static_cast<size_t>(fine.nodeCount));
    Array<uint8_t> done(static_cast<size_t>(fine.nodeCount), 0);
    for (int64_t e = 0; e < elementCount; ++e)
      for (int r = 0; r < Nf; ++r) {
        const int32_t i = fine.elementNodes[Nf * e + r];
        if (done[i]) continue;
        done[i] = 1;
        for (int c = 0; c < N; ++c)
          if (E[r * N + c] != 0.0) rows[i].emplace_back(level.elementNodes[N * e + c], E[r * N + c]);
      }
    P.rowStart.assign(static_cast<size_t>(fine.nodeCount) + 1, 0);
    for (int32_t i = 0; i < fine.nodeCount; ++i) {
      if (!done[i])
        return fail(Status::InvalidArgument, "fine node %d belongs to no element (fineNodeCount = %d)", i,
                    fine.nodeCount);
      for (const auto& [c, w] : rows[i]) P.columns.push_back(c), P.weights.push_back(w);
      P.rowStart[i + 1] = static_cast<int32_t>(P.columns.size());
    }
    h.prolongations.push_back(std::move(P));
    h.levels.push_back(std::move(level));
  }
  *out = std::move(h);
  return Status::Ok;
}

}  // namespace vp
