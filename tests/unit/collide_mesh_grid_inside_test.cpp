// Grid points inside a prepared mesh collider by row parity (collide/mesh_grid_inside.h): the
// same answer as solidContains's ray cast at every point off the surface, for a torus (rows
// that cross it four times) as a deforming surface, placed off the grid's lattice.
#include <gtest/gtest.h>

#include "collide/mesh_grid_inside.h"
#include "geometry_test_shapes.h"

namespace vp {
namespace {

TEST(MeshGridInside, RowParityAgreesWithTheRayCastAtEveryPoint) {
  const SurfaceMesh s = test::torus(0.45, 0.17, 48, 24);
  Array<Eigen::Vector3d> vertices;
  for (const Eigen::Vector3d& v : s.vertices) vertices.push_back(v + Eigen::Vector3d(0.751, 0.733, 0.727));
  Array<Eigen::Vector3i> triangles;
  for (const auto& t : s.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  PreparedCollider torus;
  ASSERT_EQ(prepareDeformingSurface(vertices, triangles, &torus), Status::Ok) << lastError();
  SampleGrid grid;
  grid.origin = Eigen::Vector3d(0.1, 0.12, 0.09);
  grid.spacing = 1.0 / 29.0;
  grid.offset = 0.5;
  grid.count = {{40, 41, 39}};
  Array<uint8_t> inside;
  ASSERT_EQ(meshGridInside(torus, grid, "test", &inside), Status::Ok) << lastError();
  ASSERT_EQ(inside.size(), size_t(40 * 41 * 39));
  int64_t in = 0;
  for (int64_t k = 0; k < grid.count[2]; ++k)
    for (int64_t j = 0; j < grid.count[1]; ++j)
      for (int64_t i = 0; i < grid.count[0]; ++i) {
        const Eigen::Vector3d x = grid.origin + grid.spacing * (Eigen::Vector3d(double(i), double(j), double(k)) +
                                                                Eigen::Vector3d::Constant(grid.offset));
        const size_t n = static_cast<size_t>((k * grid.count[1] + j) * grid.count[0] + i);
        ASSERT_EQ(inside[n] != 0, solidContains(torus, x)) << i << " " << j << " " << k;
        in += inside[n];
      }
  EXPECT_GT(in, 1000);  // the torus's tube holds many points: the comparison is not all outside
}

}  // namespace
}  // namespace vp
