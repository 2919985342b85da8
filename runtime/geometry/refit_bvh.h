// A bounding volume hierarchy over a triangle surface that moves but keeps its triangles (a
// deformable's render surface): the tree's shape is built once, and its boxes are refit to
// new positions in one pass (children come after their parent, so a reverse sweep sees every
// child before its parent). A refit tree stays exact (every box holds its triangles) but
// loosens as the surface deforms far from the shape it was built for; rebuild() then helps.
// Scene queries use it so that a batch of rays costs one refit plus log-time traversals
// instead of every triangle per ray.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/allocator.h"
#include "core/math_types.h"

namespace vp {

class RefitBvh {
 public:
  using Triangle = std::array<int32_t, 3>;

  // The tree's shape for `triangles` at `positions` (median splits on the longest axis of
  // the centroids, leaves of at most kLeafSize triangles).
  void rebuild(const Array<Vec3>& positions, const Array<Triangle>& triangles);
  // The boxes for new positions of the same triangles. With `margins` (one per triangle),
  // each triangle's box is grown by its margin on every side: a box query then also finds
  // what the triangle may reach by moving (pair_contacts.h).
  void refit(const Array<Vec3>& positions, const Array<Triangle>& triangles, const Array<double>* margins = nullptr);
  bool empty() const { return nodes_.empty(); }
  // The whole surface's box (the root's); an empty tree has lo > hi.
  Vec3 lo() const { return nodes_.empty() ? Vec3::Constant(1.0) : nodes_[0].box.lo; }
  Vec3 hi() const { return nodes_.empty() ? Vec3::Constant(-1.0) : nodes_[0].box.hi; }

  // visit(triangle) for every triangle whose own box (grown by its margin) overlaps [lo, hi],
  // in the tree's order.
  template <class Visit>
  void visitBox(const Vec3& lo, const Vec3& hi, const Visit& visit) const {
    if (nodes_.empty()) return;
    int stack[kMaxDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[static_cast<size_t>(stack[--top])];
      if (!overlaps(n.box, lo, hi)) continue;
      if (n.count > 0) {
        for (int i = n.first; i < n.first + n.count; ++i)
          if (overlaps(triangleBoxes_[static_cast<size_t>(i)], lo, hi)) visit(order_[static_cast<size_t>(i)]);
      } else {
        stack[top++] = n.left;
        stack[top++] = n.right;
      }
    }
  }

  // visit(triangle, limit) for the triangles whose leaf box the ray origin + t direction,
  // t in [0, limit], passes through; visit returns the new limit (a nearer hit shortens the
  // search; return limit unchanged to see every crossing).
  template <class Visit>
  void visitRay(const Vec3& origin, const Vec3& direction, double limit, const Visit& visit) const {
    if (nodes_.empty()) return;
    const Vec3 inverse = direction.cwiseInverse();
    int stack[kMaxDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[static_cast<size_t>(stack[--top])];
      if (!rayMeetsBox(origin, inverse, limit, n.box.lo, n.box.hi)) continue;
      if (n.count > 0) {
        for (int i = 0; i < n.count; ++i) limit = visit(order_[static_cast<size_t>(n.first + i)], limit);
      } else {
        stack[top++] = n.left;
        stack[top++] = n.right;
      }
    }
  }

  static constexpr int kLeafSize = 4;
  static constexpr int kMaxDepth = 60;  // the traversal stacks' size follows

 private:
  struct Box {
    Vec3 lo, hi;
  };
  struct Node {
    Box box;
    int first = 0, count = 0;   // leaf: order_[first, first + count)
    int left = -1, right = -1;  // inner node (count == 0)
  };
  static bool overlaps(const Box& b, const Vec3& lo, const Vec3& hi) {
    return !((b.lo.array() > hi.array()).any() || (b.hi.array() < lo.array()).any());
  }
  int build(const Array<Vec3>& centroids, int first, int count, int depth);
  static bool rayMeetsBox(const Vec3& origin, const Vec3& inverse, double limit, const Vec3& lo, const Vec3& hi);

  Array<Node> nodes_;
  Array<int32_t> order_;  // triangle ids in leaf order
  Array<Box> triangleBoxes_;  // in leaf order: a leaf's box is not tight on each triangle
};

}  // namespace vp
