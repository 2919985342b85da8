// Closed triangle surfaces built in code for the geometry tests (outward, counter-clockwise).
#pragma once

#include "geometry/surface_mesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace vp::test {

// The box [lo, hi], 12 triangles.
inline SurfaceMesh boxSurface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  SurfaceMesh s;
  for (int i = 0; i < 8; ++i)
    s.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  // Each face as a quad (a, b, c, d) counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    s.triangles.push_back({{q[0], q[1], q[2]}});
    s.triangles.push_back({{q[0], q[2], q[3]}});
  }
  return s;
}

// Icosahedron subdivided `levels` times, vertices on the sphere of radius `r`.
inline SurfaceMesh icosphere(int levels, double r) {
  SurfaceMesh s;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& p : v) s.vertices.push_back(Eigen::Vector3d(p[0], p[1], p[2]).normalized());
  s.triangles = {{{0, 11, 5}}, {{0, 5, 1}},  {{0, 1, 7}},  {{0, 7, 10}}, {{0, 10, 11}}, {{1, 5, 9}},  {{5, 11, 4}},
                 {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},  {{3, 9, 4}},  {{3, 4, 2}},   {{3, 2, 6}},  {{3, 6, 8}},
                 {{3, 8, 9}},  {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}}, {{8, 6, 7}},   {{9, 8, 1}}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int32_t, int32_t>, int32_t> midpoint;
    auto mid = [&](int32_t a, int32_t b) {
      auto key = std::minmax(a, b);
      auto found = midpoint.find(key);
      if (found != midpoint.end()) return found->second;
      s.vertices.push_back((s.vertices[a] + s.vertices[b]).normalized());
      const int32_t m = static_cast<int32_t>(s.vertices.size() - 1);
      midpoint.emplace(key, m);
      return m;
    };
    Array<std::array<int32_t, 3>> finer;
    for (const auto& tri : s.triangles) {
      const int32_t a = mid(tri[0], tri[1]), b = mid(tri[1], tri[2]), c = mid(tri[2], tri[0]);
      finer.push_back({{tri[0], a, c}});
      finer.push_back({{tri[1], b, a}});
      finer.push_back({{tri[2], c, b}});
      finer.push_back({{a, b, c}});
    }
    s.triangles = std::move(finer);
  }
  for (auto& p : s.vertices) p *= r;
  return s;
}

// Volume enclosed by a closed, outward-oriented surface (divergence theorem).
inline double enclosedVolume(const SurfaceMesh& s) {
  double v = 0.0;
  for (const auto& t : s.triangles)
    v += s.vertices[t[0]].dot(s.vertices[t[1]].cross(s.vertices[t[2]])) / 6.0;
  return v;
}

// Reverses every triangle when the surface is inward (negative enclosed volume).
inline void orientOutward(SurfaceMesh* s) {
  if (test::enclosedVolume(*s) < 0.0)
    for (auto& t : s->triangles) std::swap(t[1], t[2]);
}

// The torus around the z axis with tube centre radius `major` and tube radius `minor`, as a
// `around` x `across` grid of quadrilaterals, each split in two.
inline SurfaceMesh torus(double major, double minor, int around, int across) {
  SurfaceMesh s;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const double u = 2.0 * M_PI * i / around, v = 2.0 * M_PI * j / across;
      const double ring = major + minor * std::cos(v);
      s.vertices.emplace_back(ring * std::cos(u), ring * std::sin(u), minor * std::sin(v));
    }
  auto id = [&](int i, int j) { return static_cast<int32_t>((i % around) * across + (j % across)); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      s.triangles.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      s.triangles.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  orientOutward(&s);
  return s;
}

// Distance from the origin, along the unit direction d, to where the ray leaves the capsule
// of radius `w` around the segment from the origin to length * axis (axis a unit vector).
inline double capsuleExit(const Eigen::Vector3d& d, const Eigen::Vector3d& axis, double length, double w) {
  const double c = d.dot(axis), s = std::sqrt(std::max(0.0, 1.0 - c * c));
  if (c <= 0.0) return w;                      // backwards: the cap around the origin
  if (w * c <= length * s) return w / s;        // through the side
  return length * c + std::sqrt(w * w - length * length * s * s);  // through the far cap
}

// A star: a ball of radius `core` with six arms, capsules of radius `arm` reaching `reach`
// from the centre along the axes of a tilted frame (so that the arms cross lattice rows
// obliquely). The union is star-shaped about the origin, so it is the icosphere of `levels`
// with each vertex moved out to the union's boundary along its direction.
inline SurfaceMesh star(int levels, double core, double arm, double reach) {
  SurfaceMesh s = icosphere(levels, 1.0);
  const Eigen::Matrix3d tilt =
      (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  for (auto& p : s.vertices) {
    double r = core;
    for (int k = 0; k < 3; ++k)
      for (double sign : {-1.0, 1.0}) r = std::max(r, capsuleExit(p, sign * tilt.col(k), reach - arm, arm));
    p *= r;
  }
  return s;
}

}  // namespace vp::test
