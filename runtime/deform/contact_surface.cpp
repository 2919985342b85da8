#include "deform/contact_surface.h"

#include <algorithm>

namespace vp {

void ContactSurface::build(const SurfaceMesh& boundary, const Array<int32_t>& vertexNode,
                           const Array<int32_t>& elementNodes, int nodesPerElement, int32_t nodeCount) {
  vertexNode_ = vertexNode;
  triangles_.assign(boundary.triangles.begin(), boundary.triangles.end());
  triangleNodes_.resize(triangles_.size());
  for (size_t t = 0; t < triangles_.size(); ++t)
    for (int k = 0; k < 3; ++k) triangleNodes_[t][k] = vertexNode_[triangles_[t][k]];
  // Each node's corner neighbours through the elements (control points of higher degrees
  // included, as their element's corners' neighbours), sorted per node (a CSR list).
  const size_t elements = elementNodes.size() / static_cast<size_t>(nodesPerElement);
  std::vector<std::vector<int32_t>> lists(static_cast<size_t>(nodeCount));
  for (size_t e = 0; e < elements; ++e)
    for (int a = 0; a < nodesPerElement; ++a)
      for (int b = 0; b < 4; ++b) lists[elementNodes[nodesPerElement * e + a]].push_back(elementNodes[nodesPerElement * e + b]);
  neighbourStart_.assign(static_cast<size_t>(nodeCount) + 1, 0);
  neighbourList_.clear();
  for (int32_t i = 0; i < nodeCount; ++i) {
    std::vector<int32_t>& l = lists[static_cast<size_t>(i)];
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
    neighbourList_.insert(neighbourList_.end(), l.begin(), l.end());
    neighbourStart_[i + 1] = static_cast<int32_t>(neighbourList_.size());
  }
  Array<uint8_t> onBoundary(static_cast<size_t>(nodeCount), 0);
  for (int32_t n : vertexNode_) onBoundary[n] = 1;
  hasInteriorNode_ = false;
  for (size_t e = 0; e < elements && !hasInteriorNode_; ++e)
    for (int a = 0; a < 4; ++a) hasInteriorNode_ = hasInteriorNode_ || !onBoundary[elementNodes[nodesPerElement * e + a]];
  positions_.clear();
  bvh_ = RefitBvh();
}

void ContactSurface::refit(const Array<double>& x, const Array<double>& v, double h) {
  positions_.resize(vertexNode_.size());
  for (size_t i = 0; i < vertexNode_.size(); ++i) {
    const int64_t n = vertexNode_[i];
    positions_[i] = Vec3(x[3 * n], x[3 * n + 1], x[3 * n + 2]);
  }
  auto velocity = [&](int64_t n) { return Vec3(v[3 * n], v[3 * n + 1], v[3 * n + 2]); };
  frameVelocity_ = Vec3::Zero();
  for (int32_t n : vertexNode_) frameVelocity_ += velocity(n);
  if (!vertexNode_.empty()) frameVelocity_ /= static_cast<double>(vertexNode_.size());
  margins_.resize(triangleNodes_.size());
  for (size_t t = 0; t < triangleNodes_.size(); ++t) {
    double fastest = 0.0;
    for (int32_t n : triangleNodes_[t]) fastest = std::max(fastest, (velocity(n) - frameVelocity_).norm());
    margins_[t] = h * fastest;
  }
  nodeNormals_.assign(static_cast<size_t>(nodeCount()), Vec3::Zero());
  for (const RefitBvh::Triangle& t : triangles_) {
    const Vec3 areaNormal = (positions_[t[1]] - positions_[t[0]]).cross(positions_[t[2]] - positions_[t[0]]);
    for (int k = 0; k < 3; ++k) nodeNormals_[vertexNode_[t[k]]] += areaNormal;
  }
  for (Vec3& n : nodeNormals_)
    if (n.squaredNorm() > 0.0) n.normalize();
  if (bvh_.empty()) bvh_.rebuild(positions_, triangles_);
  bvh_.refit(positions_, triangles_, &margins_);
}

ContactSurface::NodeList ContactSurface::neighbourList(int32_t a) const {
  if (a < 0 || static_cast<size_t>(a) + 1 >= neighbourStart_.size()) return {};
  return {neighbourList_.data() + neighbourStart_[a], neighbourList_.data() + neighbourStart_[a + 1]};
}

}  // namespace vp
