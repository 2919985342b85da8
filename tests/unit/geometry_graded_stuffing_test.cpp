// Isosurface stuffing on the octree-graded lattice (graded_bcc_lattice.h): positive, conforming
// tets (every face inside the body shared by two tets, so no hanging vertex), the volume kept as
// on the uniform lattice, the dihedral angles within the bounds, fewer tets than uniform,
// grading 0 equal to the uniform output, and the grading argument's errors.
#include "geometry/isosurface_stuffing.h"

#include "deform/deformable_mesh_source.h"
#include "geometry/closest_point_on_triangle.h"
#include "geometry/graded_bcc_lattice.h"
#include "geometry/mesh_quality.h"
#include "geometry/refit_bvh.h"

#include "geometry_test_shapes.h"
#include "tet_mesh_conformity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

namespace vp {
namespace {

const int kDefaultResolution = DeformableMeshSource{}.voxelResolution;
constexpr int kTestGrading = 3;

double distanceToSurface(const RefitBvh& bvh, const SurfaceMesh& surface, const Eigen::Vector3d& p, double radius) {
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d r = Eigen::Vector3d::Constant(radius);
  bvh.visitBox(p - r, p + r, [&](int32_t t) {
    const auto& tri = surface.triangles[static_cast<size_t>(t)];
    best = std::min(best, (closestPointOnTriangle(p, surface.vertices[tri[0]], surface.vertices[tri[1]],
                                                  surface.vertices[tri[2]]) - p).norm());
  });
  return best;
}

struct Graded {
  TetMesh mesh;
  StuffingReport report;
  TetMeshQuality quality;
  double volumeError = 0.0;
};

Graded stuff(const SurfaceMesh& surface, int resolution, int grading) {
  Graded g;
  EXPECT_EQ(tetrahedralizeByStuffing(surface, resolution, &g.mesh, &g.report, StuffingBoundary::KeepVolume, grading),
            Status::Ok)
      << lastError();
  g.quality = tetMeshQuality(g.mesh, surface);
  g.volumeError = (g.quality.tetVolume - g.quality.surfaceVolume) / g.quality.surfaceVolume;
  return g;
}

// Positive tets; conforming, and every face used once lies on the boundary (within a cell of
// the surface): a hanging vertex inside would leave faces used once deep inside.
void expectValidGraded(const SurfaceMesh& surface, const Graded& g) {
  ASSERT_FALSE(g.mesh.tets.empty());
  for (size_t t = 0; t < g.mesh.tets.size(); ++t) ASSERT_GT(signedTetVolume(g.mesh, t), 0.0) << "tet " << t;
  RefitBvh bvh;
  bvh.rebuild(surface.vertices, surface.triangles);
  const double h = g.report.grid.cellSize;
  double worst = 0.0;
  for (const auto& face : test::boundaryFaces(g.mesh))
    for (int32_t v : face) worst = std::max(worst, distanceToSurface(bvh, surface, g.mesh.vertices[v], 2 * h) / h);
  EXPECT_LT(worst, 1.0) << "a face used by one tet away from the surface";
  EXPECT_GT(g.quality.minDihedralDegrees, kGradedStuffingMinDihedralDegrees);
  EXPECT_LT(g.quality.maxDihedralDegrees, kGradedStuffingMaxDihedralDegrees);
}

void expectGradedKeepsTheVolume(const SurfaceMesh& surface, int resolution) {
  const Graded g = stuff(surface, resolution, kTestGrading);
  expectValidGraded(surface, g);
  EXPECT_LT(std::fabs(g.volumeError), 0.03) << g.volumeError;
}

TEST(GeometryGradedStuffing, SphereAtTheDefaultResolution) {
  expectGradedKeepsTheVolume(test::icosphere(4, 1.0), kDefaultResolution);
}

TEST(GeometryGradedStuffing, TorusAtTheDefaultResolution) {
  expectGradedKeepsTheVolume(test::torus(1.0, 0.35, 96, 48), kDefaultResolution);
}

TEST(GeometryGradedStuffing, ThinArmedStarAtTheDefaultResolution) {
  expectGradedKeepsTheVolume(test::star(5, 0.35, 0.12, 1.0), kDefaultResolution);
}

TEST(GeometryGradedStuffing, DuckAtTheDefaultResolution) {
  constexpr const char* kDuck = "/usr/share/assimp/models/Collada/duck.dae";
  SurfaceMesh duck;
  // scripts/setup.sh installs assimp-testmodels: a missing duck is a broken set-up, not a skip.
  ASSERT_TRUE(std::filesystem::exists(kDuck)) << kDuck << " (assimp-testmodels) is not installed";
  ASSERT_EQ(loadSurfaceMesh(kDuck, &duck), Status::Ok) << lastError();
  expectGradedKeepsTheVolume(duck, kDefaultResolution);
}

// Where the interior is deep enough to coarsen, the graded mesh is valid at a finer resolution
// too and has markedly fewer tets than the uniform one, with the volume as close.
TEST(GeometryGradedStuffing, FewerTetsThanUniformOnTheSphere) {
  const SurfaceMesh sphere = test::icosphere(4, 1.0);
  for (int resolution : {24, 32}) {
    const Graded uniform = stuff(sphere, resolution, 0);
    const Graded graded = stuff(sphere, resolution, kTestGrading);
    expectValidGraded(sphere, graded);
    EXPECT_LT(std::fabs(graded.volumeError), 0.03) << graded.volumeError;
    const double ratio = double(uniform.mesh.tets.size()) / double(graded.mesh.tets.size());
    EXPECT_GT(ratio, resolution == 24 ? 1.25 : 1.5) << uniform.mesh.tets.size() << " / " << graded.mesh.tets.size();
    std::printf("sphere %d: uniform %zu tets, graded %zu tets (%.2fx), volume error %.2e / %.2e\n", resolution,
                uniform.mesh.tets.size(), graded.mesh.tets.size(), ratio, uniform.volumeError, graded.volumeError);
  }
}

TEST(GeometryGradedStuffing, GradingZeroIsTheUniformOutput) {
  const SurfaceMesh star = test::star(5, 0.35, 0.12, 1.0);
  TetMesh plain, zero;
  ASSERT_EQ(tetrahedralizeByStuffing(star, 17, &plain), Status::Ok) << lastError();
  ASSERT_EQ(tetrahedralizeByStuffing(star, 17, &zero, nullptr, StuffingBoundary::KeepVolume, 0), Status::Ok);
  EXPECT_EQ(plain.tets, zero.tets);
  EXPECT_EQ(plain.vertices, zero.vertices);
}

TEST(GeometryGradedStuffing, Deterministic) {
  const SurfaceMesh sphere = test::icosphere(3, 1.0);
  const Graded first = stuff(sphere, 24, kTestGrading), second = stuff(sphere, 24, kTestGrading);
  EXPECT_EQ(first.mesh.tets, second.mesh.tets);
  EXPECT_EQ(first.mesh.vertices, second.mesh.vertices);
}

TEST(GeometryGradedStuffing, BadGradingIsNamedAndChangesNothing) {
  const SurfaceMesh box = test::boxSurface({0, 0, 0}, {1, 1, 1});
  TetMesh out;
  out.vertices.emplace_back(1, 1, 1);
  StuffingReport report;
  report.cutPoints = 77;
  for (int grading : {-1, kMaxStuffingGrading + 1}) {
    EXPECT_EQ(tetrahedralizeByStuffing(box, 8, &out, &report, StuffingBoundary::KeepVolume, grading),
              Status::InvalidArgument);
    EXPECT_NE(std::string(lastError()).find("grading " + std::to_string(grading)), std::string::npos) << lastError();
    EXPECT_EQ(out.vertices.size(), 1u);
    EXPECT_TRUE(out.tets.empty());
    EXPECT_EQ(report.cutPoints, 77);
  }
}

}  // namespace
}  // namespace vp
