// Isosurface stuffing: volume against the surface's (divergence theorem), the paper's dihedral
// angle bounds, positive and conforming tets whose boundary lies on the surface (OnSurface) or
// within the offset's bound of it (KeepVolume, the default: stuffing_offset.h), determinism,
// errors, and the render surface embedded in the result.
#include "geometry/isosurface_stuffing.h"

#include "deform/deformable_mesh_source.h"
#include "geometry/closest_point_on_triangle.h"
#include "geometry/embedding.h"
#include "geometry/mesh_quality.h"
#include "geometry/refit_bvh.h"

#include "geometry_test_shapes.h"
#include "tet_mesh_conformity.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace vp {
namespace {

const int kDefaultResolution = DeformableMeshSource{}.voxelResolution;
constexpr const char* kDuck = "/usr/share/assimp/models/Collada/duck.dae";

// Arms of radius 0.12 reaching 1 from the centre: 0.24 across in a 2.2 wide star, about 1.3
// cells at the default resolution.
SurfaceMesh thinArmedStar() { return test::star(5, 0.35, 0.12, 1.0); }
SurfaceMesh testTorus() { return test::torus(1.0, 0.35, 96, 48); }

bool loadDuck(SurfaceMesh* duck) { return std::filesystem::exists(kDuck) && ok(loadSurfaceMesh(kDuck, duck)); }

// Distance from p to the nearest triangle of `surface` within `radius` (infinity if none).
double surfaceDistanceWithin(const RefitBvh& bvh, const SurfaceMesh& surface, const Eigen::Vector3d& p,
                             double radius) {
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d r = Eigen::Vector3d::Constant(radius);
  bvh.visitBox(p - r, p + r, [&](int32_t t) {
    const auto& tri = surface.triangles[static_cast<size_t>(t)];
    const Eigen::Vector3d q =
        closestPointOnTriangle(p, surface.vertices[tri[0]], surface.vertices[tri[1]], surface.vertices[tri[2]]);
    best = std::min(best, (q - p).norm());
  });
  return best;
}

struct Stuffed {
  TetMesh mesh;
  StuffingReport report;
  TetMeshQuality quality;
  double volumeError = 0.0;           // (tets - surface) / surface
  double maxBoundaryDistance = 0.0;   // of a boundary vertex to the surface, in cells
};

Stuffed stuff(const SurfaceMesh& surface, int resolution,
              StuffingBoundary boundary = StuffingBoundary::KeepVolume) {
  Stuffed s;
  EXPECT_EQ(tetrahedralizeByStuffing(surface, resolution, &s.mesh, &s.report, boundary), Status::Ok) << lastError();
  s.quality = tetMeshQuality(s.mesh, surface);
  s.volumeError = (s.quality.tetVolume - s.quality.surfaceVolume) / s.quality.surfaceVolume;
  return s;
}

// Every tet positive, the mesh conforming, every boundary vertex near the surface: OnSurface,
// on it within round-off (all are cut points or lattice vertices warped onto one); KeepVolume,
// within kMaxOffsetCells of it, the cap on the offset's move of a vertex that was on it (the
// moves put the boundary off the surface on purpose, so the round-off check cannot apply).
// Either way within one cell.
void expectValidStuffing(const SurfaceMesh& surface, Stuffed* s,
                         StuffingBoundary boundary = StuffingBoundary::KeepVolume) {
  const TetMesh& mesh = s->mesh;
  ASSERT_FALSE(mesh.tets.empty());
  for (size_t t = 0; t < mesh.tets.size(); ++t) ASSERT_GT(signedTetVolume(mesh, t), 0.0) << "tet " << t;
  RefitBvh bvh;
  bvh.rebuild(surface.vertices, surface.triangles);
  const double h = s->report.grid.cellSize;
  for (const auto& face : test::boundaryFaces(mesh))
    for (int32_t v : face)
      s->maxBoundaryDistance =
          std::max(s->maxBoundaryDistance, surfaceDistanceWithin(bvh, surface, mesh.vertices[v], h) / h);
  EXPECT_LT(s->maxBoundaryDistance, 1.0) << "a boundary vertex more than a cell from the surface";
  if (boundary == StuffingBoundary::OnSurface) {
    EXPECT_LT(s->maxBoundaryDistance, 1e-12) << "a boundary vertex off the surface";
  } else {
    EXPECT_LE(s->maxBoundaryDistance, kMaxOffsetCells * (1.0 + 1e-9)) << "a boundary vertex past the offset's cap";
  }
  EXPECT_EQ(s->report.missedCuts, 0);
}

void expectWithinAngleBounds(const Stuffed& s) {
  EXPECT_GT(s.quality.minDihedralDegrees, kStuffingMinDihedralDegrees);
  EXPECT_LT(s.quality.maxDihedralDegrees, kStuffingMaxDihedralDegrees);
}

// Valid, within the angle bounds, and the tets' volume within 3% of the surface's.
void expectKeepsTheVolume(const SurfaceMesh& surface, int resolution) {
  Stuffed s = stuff(surface, resolution);
  expectValidStuffing(surface, &s);
  expectWithinAngleBounds(s);
  EXPECT_LT(std::fabs(s.volumeError), 0.03) << s.volumeError;
}

TEST(GeometryIsosurfaceStuffing, SphereAtTheDefaultResolution) {
  expectKeepsTheVolume(test::icosphere(4, 1.0), kDefaultResolution);
}

TEST(GeometryIsosurfaceStuffing, DuckAtTheDefaultResolution) {
  SurfaceMesh duck;
  if (!loadDuck(&duck)) GTEST_SKIP() << kDuck << " (assimp-testmodels) is not installed";
  expectKeepsTheVolume(duck, kDefaultResolution);
}

// At the default resolution the torus's tube is 3.1 cells across and the star's arms 1.3-1.6:
// their boundary triangles, chords of the surface, lose more than 3% of the volume, which the
// offset (stuffing_offset.h) gives back.
TEST(GeometryIsosurfaceStuffing, TorusAtTheDefaultResolution) { expectKeepsTheVolume(testTorus(), kDefaultResolution); }

TEST(GeometryIsosurfaceStuffing, ThinArmedStarAtTheDefaultResolution) {
  expectKeepsTheVolume(thinArmedStar(), kDefaultResolution);
}

// Without the offset the boundary lies on the surface and the error is the chords': the mesh
// loses volume on convex tubes, and halving the cell size cuts the loss by about four (at least
// three here, the lattice's placement varies).
TEST(GeometryIsosurfaceStuffing, ChordsOnTheSurfaceConvergeAtSecondOrder) {
  for (const SurfaceMesh& surface : {testTorus(), thinArmedStar()}) {
    Stuffed s = stuff(surface, kDefaultResolution, StuffingBoundary::OnSurface);
    expectValidStuffing(surface, &s, StuffingBoundary::OnSurface);
    expectWithinAngleBounds(s);
    const double coarse = s.volumeError;
    const double fine = stuff(surface, 2 * kDefaultResolution, StuffingBoundary::OnSurface).volumeError;
    EXPECT_LT(coarse, 0.0);
    EXPECT_LT(fine, 0.0);
    EXPECT_LT(3.0 * std::fabs(fine), std::fabs(coarse)) << coarse << " -> " << fine;
  }
}

// The offset gives back most of the chords' loss, and what is left falls at least fourfold when
// the cell is halved. The sphere's remainder at the default is already near the size of its own
// facets' effects, so only the first check is made on it.
TEST(GeometryIsosurfaceStuffing, TheOffsetGivesBackTheChordsVolume) {
  SurfaceMesh duck;
  std::vector<std::pair<SurfaceMesh, bool>> surfaces = {
      {test::icosphere(4, 1.0), false}, {testTorus(), true}, {thinArmedStar(), true}};
  if (loadDuck(&duck)) surfaces.emplace_back(duck, true);
  for (const auto& [surface, refine] : surfaces) {
    const double chords = stuff(surface, kDefaultResolution, StuffingBoundary::OnSurface).volumeError;
    const double coarse = stuff(surface, kDefaultResolution).volumeError;
    EXPECT_LT(4.0 * std::fabs(coarse), std::fabs(chords)) << chords << " -> " << coarse;
    if (!refine) continue;
    const double fine = stuff(surface, 2 * kDefaultResolution).volumeError;
    EXPECT_LT(4.0 * std::fabs(fine), std::fabs(coarse)) << coarse << " -> " << fine;
  }
}

// The offset moves boundary vertices only (the tets are the same), and no tet's angles leave
// [kOffsetMinDihedralDegrees, kOffsetMaxDihedralDegrees] or, for one already outside, get worse.
// The duck at 16 cells and the star at 20 have moves that the narrower range cuts.
TEST(GeometryIsosurfaceStuffing, TheOffsetMovesTheBoundaryOnlyAndKeepsEachTetsAngles) {
  SurfaceMesh duck;
  std::vector<std::pair<SurfaceMesh, int>> cases = {
      {testTorus(), kDefaultResolution}, {thinArmedStar(), kDefaultResolution}, {thinArmedStar(), 20}};
  if (loadDuck(&duck)) cases.emplace_back(duck, 16);
  for (const auto& [surface, resolution] : cases) {
    const Stuffed before = stuff(surface, resolution, StuffingBoundary::OnSurface);
    const Stuffed after = stuff(surface, resolution);
    ASSERT_EQ(before.mesh.tets, after.mesh.tets);
    ASSERT_EQ(before.mesh.vertices.size(), after.mesh.vertices.size());
    EXPECT_GT(after.report.offset.movedVertices, 0);
    EXPECT_LT(after.report.offset.maxOffset, kMaxOffsetCells * (1.0 + 1e-12));
    std::vector<bool> onBoundary(before.mesh.vertices.size(), false);
    for (const auto& face : test::boundaryFaces(before.mesh))
      for (int32_t v : face) onBoundary[static_cast<size_t>(v)] = true;
    for (size_t v = 0; v < before.mesh.vertices.size(); ++v)
      if (!onBoundary[v]) {
        EXPECT_EQ(before.mesh.vertices[v], after.mesh.vertices[v]) << "interior vertex " << v;
      }
    for (const auto& tet : before.mesh.tets) {
      double lo0, hi0, lo1, hi1;
      const auto& x0 = before.mesh.vertices;
      const auto& x1 = after.mesh.vertices;
      tetDihedralRangeDegrees(x0[tet[0]], x0[tet[1]], x0[tet[2]], x0[tet[3]], &lo0, &hi0);
      tetDihedralRangeDegrees(x1[tet[0]], x1[tet[1]], x1[tet[2]], x1[tet[3]], &lo1, &hi1);
      // The offset checks cosines from face normals: the same angles to round-off.
      EXPECT_GE(lo1, std::min(lo0, kOffsetMinDihedralDegrees) - 1e-9);
      EXPECT_LE(hi1, std::max(hi0, kOffsetMaxDihedralDegrees) + 1e-9);
    }
  }
}

// A box whose faces lie on lattice planes: lattice vertices exactly on the surface, whose side
// ray parity decides by its tie rule; the volume is still the box's.
TEST(GeometryIsosurfaceStuffing, LatticeAlignedBox) {
  const SurfaceMesh box = test::boxSurface({0, 0, 0}, {1, 1, 1});
  TetMesh mesh;
  StuffingReport report;
  ASSERT_EQ(tetrahedralizeByStuffing(box, 4, &mesh, &report), Status::Ok) << lastError();
  for (size_t t = 0; t < mesh.tets.size(); ++t) ASSERT_GT(signedTetVolume(mesh, t), 0.0) << "tet " << t;
  test::boundaryFaces(mesh);
  const TetMeshQuality q = tetMeshQuality(mesh, box);
  EXPECT_GT(q.minDihedralDegrees, kStuffingMinDihedralDegrees);
  EXPECT_LT(q.maxDihedralDegrees, kStuffingMaxDihedralDegrees);
  EXPECT_NEAR(q.tetVolume, 1.0, 1e-12);
}

TEST(GeometryIsosurfaceStuffing, Deterministic) {
  const SurfaceMesh star = thinArmedStar();
  TetMesh first, second;
  ASSERT_EQ(tetrahedralizeByStuffing(star, 17, &first), Status::Ok) << lastError();
  ASSERT_EQ(tetrahedralizeByStuffing(star, 17, &second), Status::Ok) << lastError();
  EXPECT_EQ(first.tets, second.tets);
  EXPECT_EQ(first.vertices, second.vertices);
}

// The surface's checks are the grid's (surface_grid.h, tested through the voxel mesher too);
// here: that they name this function, and that nothing is written on error.
TEST(GeometryIsosurfaceStuffing, ErrorsNameTheArgumentAndChangeNothing) {
  TetMesh out;
  out.vertices.emplace_back(1, 1, 1);
  StuffingReport report;
  report.cutPoints = 77;
  const SurfaceMesh box = test::boxSurface({0, 0, 0}, {1, 1, 1});
  SurfaceMesh open = box;
  open.triangles.pop_back();
  const std::pair<const SurfaceMesh*, int> bad[] = {{&box, 0}, {&box, 5000}, {&open, 10}};
  const char* messages[] = {"tetrahedralizeByStuffing: resolution 0 is outside [1, 1024]", "resolution 5000",
                            "tetrahedralizeByStuffing: the surface is not closed"};
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(tetrahedralizeByStuffing(*bad[i].first, bad[i].second, &out, &report), Status::InvalidArgument);
    EXPECT_NE(std::string(lastError()).find(messages[i]), std::string::npos) << lastError();
    EXPECT_EQ(out.vertices.size(), 1u);
    EXPECT_EQ(report.cutPoints, 77);
  }
  EXPECT_EQ(tetrahedralizeByStuffing(box, 4, nullptr), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("out is null"), std::string::npos) << lastError();
}

// A part thinner than the lattice holds no lattice vertex and gives no tets.
TEST(GeometryIsosurfaceStuffing, APartThinnerThanACellMayVanish) {
  const SurfaceMesh plate = test::boxSurface({0, 0, 0.43}, {1, 1, 0.47});
  TetMesh mesh;
  ASSERT_EQ(tetrahedralizeByStuffing(plate, 5, &mesh), Status::Ok) << lastError();
  EXPECT_TRUE(mesh.tets.empty());
  EXPECT_TRUE(mesh.vertices.empty());
}

// The render surface's vertices lie on the surface while the mesh's boundary is near it (chords
// moved out by the offset: some render vertices stay outside every tet): they get the nearest
// tet, less than a cell away, and follow it by extrapolated barycentric coordinates.
TEST(GeometryIsosurfaceStuffing, RenderSurfaceEmbedsAndFollowsTheTets) {
  const SurfaceMesh sphere = test::icosphere(4, 1.0);
  Stuffed s = stuff(sphere, kDefaultResolution);
  Array<EmbeddedPoint> embedding;
  EmbeddingReport report;
  ASSERT_EQ(embedPoints(s.mesh, sphere.vertices, &embedding, &report), Status::Ok) << lastError();
  EXPECT_GT(report.outsidePoints, 0);
  EXPECT_LT(report.maxOutsideDistance, s.report.grid.cellSize);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.3, 2.0, -1.0);
  Array<Eigen::Vector3d> moved, positions;
  for (const auto& x : s.mesh.vertices) moved.push_back(R * x + t);
  ASSERT_EQ(evaluateEmbedded(s.mesh.tets, moved, embedding, &positions), Status::Ok) << lastError();
  for (size_t i = 0; i < positions.size(); ++i)
    EXPECT_LT((positions[i] - (R * sphere.vertices[i] + t)).norm(), 1e-12) << i;
}

}  // namespace
}  // namespace vp
