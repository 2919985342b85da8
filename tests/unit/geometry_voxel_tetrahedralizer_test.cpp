// Voxel tetrahedralizer: volume against analytic bounds, positive and conforming tets,
// shared vertices, determinism, errors.
#include "geometry/voxel_tetrahedralizer.h"

#include "geometry/tet_mesh_validation.h"

#include "geometry_test_files.h"
#include "geometry_test_shapes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace vp {
namespace {

// Goes through an OBJ file and assimp, as a user's render mesh would.
SurfaceMesh throughAssimp(const SurfaceMesh& surface) {
  test::TempDir dir;
  const std::string path = dir.file("surface.obj");
  EXPECT_EQ(writeSurfaceMeshObj(surface, path), Status::Ok) << lastError();
  SurfaceMesh loaded;
  EXPECT_EQ(loadSurfaceMesh(path, &loaded), Status::Ok) << lastError();
  return loaded;
}

// Checks that the mesh is a conforming tetrahedralization of a union of grid cubes:
//  - every tet positive and with the volume of 1/6 cube,
//  - no two vertices at the same place (vertices are shared),
//  - every triangle face is used by 1 or 2 tets; when by 2, with opposite orientations,
//  - a face used once lies on a cube face whose other side holds no kept cube (otherwise
//    two neighbouring cubes were split incompatibly and the face is a hanging one).
void expectConforming(const TetMesh& mesh, const VoxelGrid& grid) {
  const double h = grid.cellSize;
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    ASSERT_NEAR(signedTetVolume(mesh, t), h * h * h / 6.0, 1e-12 * h * h * h) << "tet " << t;

  std::set<std::array<int64_t, 3>> vertexCells;  // lattice coordinates
  auto lattice = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d c = (x - grid.origin) / h;
    return std::array<int64_t, 3>{{std::llround(c.x()), std::llround(c.y()), std::llround(c.z())}};
  };
  for (const auto& v : mesh.vertices) EXPECT_TRUE(vertexCells.insert(lattice(v)).second) << "duplicate vertex";

  std::set<std::array<int64_t, 3>> keptCells;
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int32_t v : mesh.tets[t]) centroid += mesh.vertices[v] / 4.0;
    const Eigen::Vector3d c = (centroid - grid.origin) / h;
    keptCells.insert({{int64_t(std::floor(c.x())), int64_t(std::floor(c.y())), int64_t(std::floor(c.z()))}});
  }
  EXPECT_EQ(static_cast<int64_t>(keptCells.size()), grid.keptCells);
  EXPECT_EQ(static_cast<int64_t>(mesh.tets.size()), 6 * grid.keptCells);

  // sorted face -> (count, orientation sign of first use)
  std::map<std::array<int32_t, 3>, std::pair<int, std::array<int32_t, 3>>> faces;
  for (const auto& tet : mesh.tets)
    for (const auto& f : kTetFaces) {
      std::array<int32_t, 3> oriented{{tet[f[0]], tet[f[1]], tet[f[2]]}}, key = oriented;
      std::sort(key.begin(), key.end());
      auto& entry = faces[key];
      if (entry.first == 1) {
        // Opposite orientation: `oriented` is an odd permutation of the first use.
        const auto& first = entry.second;
        int same = 0;
        for (int r = 0; r < 3; ++r)
          if (oriented[0] == first[r] && oriented[1] == first[(r + 1) % 3] && oriented[2] == first[(r + 2) % 3])
            ++same;
        EXPECT_EQ(same, 0) << "face shared by two tets with the same orientation";
      }
      if (entry.first == 0) entry.second = oriented;
      ++entry.first;
    }
  int64_t boundary = 0;
  for (const auto& [key, entry] : faces) {
    ASSERT_LE(entry.first, 2) << "face used by more than 2 tets";
    if (entry.first == 2) continue;
    ++boundary;
    // Outward normal of the face (as oriented in its only tet) must be axis-aligned, and the
    // cube behind it must not be kept.
    const auto& f = entry.second;
    const Eigen::Vector3d n = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    ASSERT_NEAR(n.norm(), std::fabs(n[axis]), 1e-12 * h * h) << "boundary face inside a cube (not on a cube face)";
    const Eigen::Vector3d centroid = (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3.0;
    const Eigen::Vector3d outside = (centroid + 0.5 * h * n.normalized() - grid.origin) / h;
    const std::array<int64_t, 3> cell{{int64_t(std::floor(outside.x())), int64_t(std::floor(outside.y())),
                                       int64_t(std::floor(outside.z()))}};
    EXPECT_EQ(keptCells.count(cell), 0u) << "hanging face between two kept cubes";
  }
  EXPECT_GT(boundary, 0);
}

TEST(GeometryVoxelTetrahedralizer, RaysThroughSharedEdgesCountOnce) {
  // Unit cube at resolution 4: the rays through the cell centres with y == z run exactly
  // along the diagonal edge shared by the two triangles of the x = 0 and x = 1 faces. A
  // tie rule that lets both (or neither) triangle claim the ray flips the parity of the
  // cells on those rows and loses them.
  const SurfaceMesh cube = test::boxSurface({0, 0, 0}, {1, 1, 1});
  TetMesh mesh;
  VoxelGrid grid;
  ASSERT_EQ(tetrahedralizeVoxels(cube, 4, &mesh, &grid), Status::Ok) << lastError();
  EXPECT_EQ(grid.keptCells, 64);
  EXPECT_NEAR(totalVolume(mesh), 1.0, 1e-13);
  // The same with the ray hitting triangle vertices: a cube whose corners sit on cell
  // centres' rows (y, z in {0.125 + k/4}).
  const SurfaceMesh shifted = test::boxSurface({0, 0.125, 0.125}, {1, 0.875, 0.875});
  ASSERT_EQ(tetrahedralizeVoxels(shifted, 4, &mesh, &grid), Status::Ok) << lastError();
  EXPECT_GE(totalVolume(mesh), 0.75 * 0.75);
}

TEST(GeometryVoxelTetrahedralizer, AxisAlignedBoxIsExact) {
  // A 2 x 1 x 0.5 box at resolution 8: h = 0.25, 8 x 4 x 2 cubes, all inside. Coordinates
  // are exact in float, so assimp's float storage changes nothing.
  const SurfaceMesh box = throughAssimp(test::boxSurface({-1, 0, 0.5}, {1, 1, 1}));
  TetMesh mesh;
  VoxelGrid grid;
  ASSERT_EQ(tetrahedralizeVoxels(box, 8, &mesh, &grid), Status::Ok) << lastError();
  EXPECT_EQ(grid.cells, (std::array<int32_t, 3>{{8, 4, 2}}));
  EXPECT_DOUBLE_EQ(grid.cellSize, 0.25);
  EXPECT_EQ(grid.keptCells, 64);
  EXPECT_EQ(mesh.vertices.size(), 9u * 5u * 3u);
  EXPECT_NEAR(totalVolume(mesh), 1.0, 1e-13);  // 384 tets of 1/384, round-off only
  expectConforming(mesh, grid);
  TetMeshRepairReport report;
  ASSERT_EQ(validateAndRepairTetMesh(mesh, &report), Status::Ok) << lastError();
  EXPECT_EQ(report.invertedTetsFixed, 0);
  EXPECT_EQ(report.unusedVerticesRemoved, 0);
}

// Bounds used below. Lower: every point of the solid P lies in a cell that is kept (the cell
// is either crossed by the surface or entirely inside, then its centre is inside), so the
// union of tets contains P and its volume is >= vol(P). Upper: a kept cell has its centre
// inside P or touches the surface, so all its points are within one cell diagonal sqrt(3) h
// of P; the union lies in P grown by d = sqrt(3) h, whose volume is given by Steiner's
// formula for convex P. The float storage of assimp moves the surface by ~1e-7, hence the
// 1e-6 relative slack on the lower bound.
TEST(GeometryVoxelTetrahedralizer, SphereVolumeWithinVoxelBounds) {
  const SurfaceMesh sphere = throughAssimp(test::icosphere(3, 1.0));
  const double polyhedron = test::enclosedVolume(sphere);
  double previousError = INFINITY;
  for (int resolution : {8, 16, 32}) {
    SCOPED_TRACE(resolution);
    TetMesh mesh;
    VoxelGrid grid;
    ASSERT_EQ(tetrahedralizeVoxels(sphere, resolution, &mesh, &grid), Status::Ok) << lastError();
    const double h = grid.cellSize, d = std::sqrt(3.0) * h;
    const double volume = totalVolume(mesh);
    EXPECT_NEAR(volume, grid.keptCells * h * h * h, 1e-12 * volume);
    EXPECT_GE(volume, polyhedron * (1 - 1e-6));
    EXPECT_LE(volume, 4.0 / 3.0 * M_PI * std::pow(1.0 + d, 3));
    // The excess is a shell about half a cell thick, so it must shrink as h does.
    const double error = volume - polyhedron;
    EXPECT_LT(error, previousError);
    previousError = error;
    for (size_t t = 0; t < mesh.tets.size(); ++t) ASSERT_GT(signedTetVolume(mesh, t), 0.0) << t;
    if (resolution == 16) expectConforming(mesh, grid);
  }
}

TEST(GeometryVoxelTetrahedralizer, RotatedBoxVolumeWithinSteinerBounds) {
  const double a = 1.0, b = 0.6, c = 0.35;
  SurfaceMesh box = test::boxSurface({0, 0, 0}, {a, b, c});
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (auto& v : box.vertices) v = rotation * v + Eigen::Vector3d(0.3, -0.2, 5.0);
  box = throughAssimp(box);
  TetMesh mesh;
  VoxelGrid grid;
  ASSERT_EQ(tetrahedralizeVoxels(box, 20, &mesh, &grid), Status::Ok) << lastError();
  const double d = std::sqrt(3.0) * grid.cellSize;
  const double volume = totalVolume(mesh);
  EXPECT_GE(volume, a * b * c * (1 - 1e-6));
  EXPECT_LE(volume, a * b * c + 2 * (a * b + b * c + c * a) * d + M_PI * (a + b + c) * d * d + 4.0 / 3.0 * M_PI * d * d * d);
  expectConforming(mesh, grid);
}

TEST(GeometryVoxelTetrahedralizer, ThinShapeKeepsSurfaceCells) {
  // A plate thinner than a cell: no cell centre is inside it, yet it must be covered.
  const SurfaceMesh plate = test::boxSurface({0, 0, 0.43}, {1, 1, 0.47});
  TetMesh mesh;
  VoxelGrid grid;
  ASSERT_EQ(tetrahedralizeVoxels(plate, 5, &mesh, &grid), Status::Ok) << lastError();
  EXPECT_EQ(grid.keptCells, 25);
  EXPECT_EQ(grid.surfaceCells, 25);
}

TEST(GeometryVoxelTetrahedralizer, Deterministic) {
  const SurfaceMesh sphere = test::icosphere(2, 0.7);
  TetMesh first, second;
  ASSERT_EQ(tetrahedralizeVoxels(sphere, 11, &first), Status::Ok);
  ASSERT_EQ(tetrahedralizeVoxels(sphere, 11, &second), Status::Ok);
  EXPECT_EQ(first.tets, second.tets);
  EXPECT_EQ(first.vertices, second.vertices);
}

TEST(GeometryVoxelTetrahedralizer, Errors) {
  TetMesh out;
  out.vertices.emplace_back(1, 1, 1);
  const SurfaceMesh box = test::boxSurface({0, 0, 0}, {1, 1, 1});
  auto expectInvalid = [&](const SurfaceMesh& s, int resolution, const char* fragment) {
    EXPECT_EQ(tetrahedralizeVoxels(s, resolution, &out), Status::InvalidArgument);
    EXPECT_NE(std::string(lastError()).find(fragment), std::string::npos) << lastError();
    EXPECT_EQ(out.vertices.size(), 1u);
  };
  expectInvalid(box, 0, "resolution 0");
  expectInvalid(box, 5000, "resolution 5000");
  expectInvalid(SurfaceMesh{}, 4, "0 triangles");
  SurfaceMesh open = box;
  open.triangles.pop_back();
  expectInvalid(open, 10, "not closed");
  SurfaceMesh badIndex = box;
  badIndex.triangles[3][1] = 8;
  expectInvalid(badIndex, 4, "triangle 3 corner 1 is vertex 8");
  SurfaceMesh nan = box;
  nan.vertices[2].x() = NAN;
  expectInvalid(nan, 4, "vertex 2");
}

}  // namespace
}  // namespace vp
