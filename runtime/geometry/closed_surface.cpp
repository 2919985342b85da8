#include "geometry/closed_surface.h"

#include <algorithm>
#include <map>
#include <tuple>
#include <utility>

namespace vp {

template <class Triangle>
Status checkClosedSurface(const Array<Eigen::Vector3d>& vertices, const Array<Triangle>& triangles,
                          const char* what) {
  // Weld: each vertex maps to the first vertex at exactly its position.
  std::map<std::tuple<double, double, double>, int32_t> first;
  Array<int32_t> weld(vertices.size());
  for (size_t v = 0; v < vertices.size(); ++v)
    weld[v] = first.emplace(std::make_tuple(vertices[v].x(), vertices[v].y(), vertices[v].z()), int32_t(v))
                  .first->second;
  struct Edge {
    int32_t from, to;   // welded
    int32_t a, b;       // as given, for the message
  };
  std::vector<Edge> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles) {
    const int32_t w[3] = {weld[t[0]], weld[t[1]], weld[t[2]]};
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;  // collapsed by welding: no area
    for (int c = 0; c < 3; ++c) edges.push_back(Edge{w[c], w[(c + 1) % 3], t[c], t[(c + 1) % 3]});
  }
  if (edges.empty()) return fail(Status::InvalidArgument, "%s: has no triangles with area", what);
  auto key = [](const Edge& e) { return std::make_pair(e.from, e.to); };
  std::sort(edges.begin(), edges.end(), [&](const Edge& l, const Edge& r) { return key(l) < key(r); });
  for (size_t e = 0; e < edges.size(); ++e) {
    const Edge& edge = edges[e];
    const Eigen::Vector3d& p = vertices[edge.a];
    const Eigen::Vector3d& q = vertices[edge.b];
    if (e + 1 < edges.size() && key(edges[e + 1]) == key(edge))
      return fail(Status::InvalidArgument,
                  "%s: is not closed: edge (%d, %d) from (%g, %g, %g) to (%g, %g, %g) is used twice in the same "
                  "direction (non-manifold or flipped triangles)",
                  what, edge.a, edge.b, p.x(), p.y(), p.z(), q.x(), q.y(), q.z());
    const std::pair<int32_t, int32_t> opposite(edge.to, edge.from);
    const auto match = std::lower_bound(edges.begin(), edges.end(), opposite,
                                        [&](const Edge& l, const std::pair<int32_t, int32_t>& r) { return key(l) < r; });
    if (match == edges.end() || key(*match) != opposite)
      return fail(Status::InvalidArgument,
                  "%s: is not closed: edge (%d, %d) from (%g, %g, %g) to (%g, %g, %g) borders a hole (no triangle "
                  "on its other side)",
                  what, edge.a, edge.b, p.x(), p.y(), p.z(), q.x(), q.y(), q.z());
  }
  return Status::Ok;
}

template Status checkClosedSurface(const Array<Eigen::Vector3d>&, const Array<std::array<int32_t, 3>>&, const char*);
template Status checkClosedSurface(const Array<Eigen::Vector3d>&, const Array<Eigen::Vector3i>&, const char*);

}  // namespace vp
