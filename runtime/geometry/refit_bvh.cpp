#include "geometry/refit_bvh.h"

#include <algorithm>
#include <cmath>

namespace vp {

void RefitBvh::rebuild(const Array<Vec3>& positions, const Array<Triangle>& triangles) {
  // Built apart and swapped in: a refused allocation (the host allocator may refuse any) leaves
  // this tree as it was instead of half built, with inner nodes whose children were never set.
  RefitBvh fresh;
  fresh.order_.resize(triangles.size());
  Array<Vec3> centroids(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    fresh.order_[t] = static_cast<int32_t>(t);
    const Triangle& tri = triangles[t];
    centroids[t] = (positions[tri[0]] + positions[tri[1]] + positions[tri[2]]) / 3.0;
  }
  if (!triangles.empty()) {
    fresh.nodes_.reserve(2 * (triangles.size() / kLeafSize + 1));
    fresh.build(centroids, 0, static_cast<int>(triangles.size()), 0);
    fresh.refit(positions, triangles);
  }
  nodes_.swap(fresh.nodes_);
  order_.swap(fresh.order_);
  triangleBoxes_.swap(fresh.triangleBoxes_);
}

int RefitBvh::build(const Array<Vec3>& centroids, int first, int count, int depth) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  if (count <= kLeafSize || depth >= kMaxDepth) {
    nodes_[static_cast<size_t>(id)].first = first;
    nodes_[static_cast<size_t>(id)].count = count;
    return id;
  }
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = first; i < first + count; ++i) {
    lo = lo.cwiseMin(centroids[static_cast<size_t>(order_[static_cast<size_t>(i)])]);
    hi = hi.cwiseMax(centroids[static_cast<size_t>(order_[static_cast<size_t>(i)])]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int mid = first + count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
                   [&](int32_t a, int32_t b) {
                     return centroids[static_cast<size_t>(a)][axis] < centroids[static_cast<size_t>(b)][axis];
                   });
  const int left = build(centroids, first, mid - first, depth + 1);
  const int right = build(centroids, mid, first + count - mid, depth + 1);
  nodes_[static_cast<size_t>(id)].left = left;
  nodes_[static_cast<size_t>(id)].right = right;
  return id;
}

void RefitBvh::refit(const Array<Vec3>& positions, const Array<Triangle>& triangles, const Array<double>* margins) {
  triangleBoxes_.resize(order_.size());
  const Box empty{Vec3::Constant(std::numeric_limits<double>::infinity()),
                  Vec3::Constant(-std::numeric_limits<double>::infinity())};
  auto grow = [](Box& b, const Box& by) {
    b.lo = b.lo.cwiseMin(by.lo);
    b.hi = b.hi.cwiseMax(by.hi);
  };
  for (size_t k = nodes_.size(); k-- > 0;) {
    Node& n = nodes_[k];
    n.box = empty;
    if (n.count > 0) {
      for (int i = n.first; i < n.first + n.count; ++i) {
        const size_t t = static_cast<size_t>(order_[static_cast<size_t>(i)]);
        const Vec3 margin = Vec3::Constant(margins ? (*margins)[t] : 0.0);
        Box& box = triangleBoxes_[static_cast<size_t>(i)];
        box = empty;
        for (int32_t v : triangles[t]) grow(box, Box{positions[static_cast<size_t>(v)] - margin,
                                                     positions[static_cast<size_t>(v)] + margin});
        grow(n.box, box);
      }
    } else {
      for (int child : {n.left, n.right}) grow(n.box, nodes_[static_cast<size_t>(child)].box);
    }
  }
}

bool RefitBvh::rayMeetsBox(const Vec3& origin, const Vec3& inverse, double limit, const Vec3& lo, const Vec3& hi) {
  double enter = 0.0, exit = limit;
  for (int k = 0; k < 3; ++k) {
    // inverse[k] is +-inf for a ray parallel to the slab: (lo - o) * inf decides as it should
    // unless the origin lies on the slab's plane (0 * inf = NaN), where the ray is kept.
    double a = (lo[k] - origin[k]) * inverse[k], b = (hi[k] - origin[k]) * inverse[k];
    if (std::isnan(a) || std::isnan(b)) continue;
    if (a > b) std::swap(a, b);
    enter = std::max(enter, a);
    exit = std::min(exit, b);
    if (enter > exit) return false;
  }
  return true;
}

}  // namespace vp
