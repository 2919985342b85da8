// Marching cubes liquid surface: closed, consistently oriented manifold for a sphere and for
// random fields (every ambiguous case), area and enclosed volume of a sphere, outward normals,
// a flat surface cut at the domain sides, identical output for any worker count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "fluid/surface/liquid_volume.h"
#include "fluid/surface/marching_cubes.h"
#include "fluid_liquid_test_util.h"

namespace vp {
namespace {

struct Surface {
  SurfaceMesh mesh;
  Array<Eigen::Vector3d> normals;
};

Surface extract(TaskSystem& tasks, const MacGridSpec& spec, const Array<double>& phi) {
  Surface s;
  MarchingCubesWorkspace workspace;
  EXPECT_EQ(extractLiquidSurface(tasks, spec, phi.data(), &s.mesh, &s.normals, workspace), Status::Ok) << lastError();
  EXPECT_EQ(s.normals.size(), s.mesh.vertices.size());
  return s;
}

// Closed and consistently oriented: every directed edge appears once and its reverse once
// (so each undirected edge has exactly two triangles, traversed in opposite directions).
void expectClosedOrientedManifold(const SurfaceMesh& mesh) {
  std::map<std::pair<int32_t, int32_t>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int s = 0; s < 3; ++s) ++directed[{t[s], t[(s + 1) % 3]}];
  int64_t bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) ++bad;
  }
  EXPECT_EQ(bad, 0) << "of " << directed.size() << " directed edges";
}

double area(const SurfaceMesh& m) {
  double sum = 0.0;
  for (const auto& t : m.triangles)
    sum += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
  return sum;
}

// Divergence theorem: V = 1/3 closed-surface integral of x.n = sum det(v0, v1, v2) / 6.
double enclosedVolume(const SurfaceMesh& m) {
  double sum = 0.0;
  for (const auto& t : m.triangles) sum += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]]));
  return sum / 6.0;
}

// Marching cubes' chords cut inside a convex surface: with nodes h apart the surface between
// crossings sags by about h^2 / (8 R) for a chord of length h, so area and volume come out
// low by O((h / R)^2) relative; at R / h = 14 that is well under 1 %, and 1.5 % bounds it with
// the orientation-dependent chord lengths (up to h sqrt(2) across a cube face).
TEST(FluidMarchingCubes, SphereIsClosedWithAreaVolumeAndOutwardNormals) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  MacGrid grid;
  ASSERT_EQ(initMacGrid(testutil::unitCubeGrid(48), testutil::kClosedTank, &grid), Status::Ok);
  const double radius = 0.3, h = grid.spec.h;
  const Eigen::Vector3d centre(0.503, 0.488, 0.512);
  const Array<double> phi =
      testutil::sampleCells(grid, [&](const Eigen::Vector3d& x) { return (x - centre).norm() - radius; });
  const Surface s = extract(*tasks, grid.spec, phi);
  ASSERT_GT(s.mesh.triangles.size(), 1000u);
  expectClosedOrientedManifold(s.mesh);
  const double exactArea = 4.0 * M_PI * radius * radius, exactVolume = 4.0 / 3.0 * M_PI * radius * radius * radius;
  const double a = area(s.mesh), v = enclosedVolume(s.mesh);
  const double heaviside = liquidVolume(*tasks, grid.spec, phi.data(), nullptr);
  double worstRadius = 0.0, worstNormal = 0.0;
  for (size_t i = 0; i < s.mesh.vertices.size(); ++i) {
    const Eigen::Vector3d r = s.mesh.vertices[i] - centre;
    worstRadius = std::max(worstRadius, std::fabs(r.norm() - radius));
    worstNormal = std::max(worstNormal, (s.normals[i] - r.normalized()).norm());
  }
  int64_t inward = 0;
  for (const auto& t : s.mesh.triangles) {
    const Eigen::Vector3d n = (s.mesh.vertices[t[1]] - s.mesh.vertices[t[0]])
                                  .cross(s.mesh.vertices[t[2]] - s.mesh.vertices[t[0]]);
    const Eigen::Vector3d mid = (s.mesh.vertices[t[0]] + s.mesh.vertices[t[1]] + s.mesh.vertices[t[2]]) / 3.0;
    if (n.dot(mid - centre) < 0.0) ++inward;
  }
  std::printf("    %zu vertices, %zu triangles; area %+.3e, volume %+.3e relative; Heaviside volume %+.3e; "
              "max |r - R| %.3f h, max normal error %.3e\n",
              s.mesh.vertices.size(), s.mesh.triangles.size(), a / exactArea - 1.0, v / exactVolume - 1.0,
              heaviside / exactVolume - 1.0, worstRadius / h, worstNormal);
  EXPECT_LT(std::fabs(a / exactArea - 1.0), 0.015);
  EXPECT_LT(std::fabs(v / exactVolume - 1.0), 0.015);
  EXPECT_LT(std::fabs(v / heaviside - 1.0), 0.02);  // the two volume measures agree
  // Linear interpolation of a distance between nodes h apart: the crossing is off by at most
  // about h^2 / (2 R) (the distance's curvature along the edge).
  EXPECT_LT(worstRadius, 0.5 * h * h / radius);
  EXPECT_LT(worstNormal, 0.05);  // central differences of a distance: O(h / R)
  EXPECT_EQ(inward, 0);
}

// Random signs exercise every cube case including the ambiguous faces and interiors: with a
// border of air the surface must still close, with consistent orientation.
TEST(FluidMarchingCubes, RandomFieldsGiveClosedOrientedSurfaces) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  MacGrid grid;
  ASSERT_EQ(initMacGrid(testutil::unitCubeGrid(12), testutil::kClosedTank, &grid), Status::Ok);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    Array<double> phi(static_cast<size_t>(grid.cellCount()));
    for (int k = 0; k < 12; ++k)
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) {
          const bool border = i == 0 || j == 0 || k == 0 || i == 11 || j == 11 || k == 11;
          phi[grid.cellIndex(i, j, k)] = border ? 1.0 : value(rng);
        }
    const Surface s = extract(*tasks, grid.spec, phi);
    ASSERT_GT(s.mesh.triangles.size(), 500u);
    expectClosedOrientedManifold(s.mesh);
    // Outward from the liquid: the enclosed volume is positive.
    EXPECT_GT(enclosedVolume(s.mesh), 0.0);
  }
}

TEST(FluidMarchingCubes, FlatSurfaceReachesTheDomainSidesAndIsDeterministic) {
  MacGridSpec spec = testutil::unitCubeGrid(10);
  spec.origin = Eigen::Vector3d(-0.2, 0.1, 0.3);
  spec.ny = 7;
  MacGrid grid;
  ASSERT_EQ(initMacGrid(spec, testutil::kClosedTank, &grid), Status::Ok);
  const double level = 0.1 + 0.437;
  const Array<double> phi = testutil::sampleCells(grid, [&](const Eigen::Vector3d& x) { return x.y() - level; });
  auto one = TaskSystem::create(TaskHooks{}, 1);
  auto two = TaskSystem::create(TaskHooks{}, 2);
  const Surface a = extract(*one, spec, phi), b = extract(*two, spec, phi);
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.normals, b.normals);
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e9), high = -low;
  for (size_t i = 0; i < a.mesh.vertices.size(); ++i) {
    EXPECT_NEAR(a.mesh.vertices[i].y(), level, 1e-12);
    EXPECT_NEAR(a.normals[i].y(), 1.0, 1e-12);
    low = low.cwiseMin(a.mesh.vertices[i]);
    high = high.cwiseMax(a.mesh.vertices[i]);
  }
  // Cut at the domain's sides: the plane covers the whole 1 x 1 cross-section.
  EXPECT_NEAR(low.x(), spec.origin.x(), 1e-12);
  EXPECT_NEAR(high.x(), spec.origin.x() + 1.0, 1e-12);
  EXPECT_NEAR(low.z(), spec.origin.z(), 1e-12);
  EXPECT_NEAR(high.z(), spec.origin.z() + 1.0, 1e-12);
  EXPECT_NEAR(area(a.mesh), 1.0, 1e-12);
  for (const auto& t : a.mesh.triangles) {
    const Eigen::Vector3d n = (a.mesh.vertices[t[1]] - a.mesh.vertices[t[0]])
                                  .cross(a.mesh.vertices[t[2]] - a.mesh.vertices[t[0]]);
    EXPECT_GT(n.y(), 0.0);  // up, out of the liquid
  }
}

}  // namespace
}  // namespace vp
