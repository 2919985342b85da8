// The graded lattice alone (graded_bcc_lattice.h), on a ball given by its lattice vertices' signs:
// the octree is balanced, finest next to any vertex that is not inside, coarser than one level
// deep inside; its tets, fine and coarse together, tile the lattice's box less the half
// octahedra on its outer faces (as the uniform lattice's do) and conform.
#include "geometry/graded_bcc_lattice.h"

#include "geometry/mesh_quality.h"
#include "geometry/tet_mesh.h"

#include "tet_mesh_conformity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace vp {
namespace {

constexpr int64_t kCubes = 40;

struct Ball {
  BccLattice lattice{Eigen::Vector3d::Zero(), 1.0, {{kCubes, kCubes, kCubes}}};
  Array<int8_t> sign;
  Ball() {
    const Eigen::Vector3d centre = Eigen::Vector3d::Constant(0.5 * double(kCubes));
    for (int64_t id = 0; id < lattice.vertexCount(); ++id)
      sign.push_back((lattice.position(id) - centre).norm() < 0.4 * double(kCubes) ? 1 : -1);
  }
};

TEST(GeometryGradedBccLattice, BalancedFinestNearTheSurfaceAndCoarseInside) {
  const Ball ball;
  const GradedBccLattice graded(ball.lattice, ball.sign, 4);
  int deepest = 0;
  for (int64_t k = 0; k < kCubes; ++k)
    for (int64_t j = 0; j < kCubes; ++j)
      for (int64_t i = 0; i < kCubes; ++i) {
        const int l = graded.level(i, j, k);
        deepest = std::max(deepest, l);
        for (int64_t dz = -1; dz <= 1; ++dz)
          for (int64_t dy = -1; dy <= 1; ++dy)
            for (int64_t dx = -1; dx <= 1; ++dx) {
              const int64_t x = i + dx, y = j + dy, z = k + dz;
              if (x < 0 || y < 0 || z < 0 || x >= kCubes || y >= kCubes || z >= kCubes) continue;
              EXPECT_LE(std::abs(graded.level(x, y, z) - l), 1) << i << " " << j << " " << k;
              // A coarse leaf's neighbour cubes have every vertex inside.
              if (l == 0) continue;
              for (int c = 0; c < 9; ++c) {
                const LatticePoint d = c == 8 ? LatticePoint{{2 * x + 1, 2 * y + 1, 2 * z + 1}}
                                              : LatticePoint{{2 * (x + (c & 1)), 2 * (y + ((c >> 1) & 1)),
                                                              2 * (z + (c >> 2))}};
                EXPECT_GT(ball.sign[size_t(ball.lattice.id(d))], 0);
              }
            }
      }
  // Blocks of four cubes inside a ball sixteen cubes in radius: larger ones would need a
  // coarser ring around them than the margin and the balance allow.
  EXPECT_EQ(deepest, 2);
  // More than a quarter of the ball's cubes merged away.
  const double ballCubes = 4.0 / 3.0 * M_PI * std::pow(0.4 * double(kCubes), 3);
  EXPECT_GT(double(kCubes * kCubes * kCubes - graded.leafCount()), 0.25 * ballCubes);
}

TEST(GeometryGradedBccLattice, TetsTileTheBoxAndConform) {
  const Ball ball;
  for (int grading : {0, 1, 4}) {
    const GradedBccLattice graded(ball.lattice, ball.sign, grading);
    TetMesh mesh;
    for (int64_t id = 0; id < ball.lattice.vertexCount(); ++id) mesh.vertices.push_back(ball.lattice.position(id));
    auto add = [&](const std::array<LatticePoint, 4>& p) {
      std::array<int32_t, 4> t{};
      for (int k = 0; k < 4; ++k) t[k] = static_cast<int32_t>(ball.lattice.id(p[k]));
      mesh.tets.push_back(t);
      if (signedTetVolume(mesh, mesh.tets.size() - 1) < 0.0) std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
      EXPECT_GT(signedTetVolume(mesh, mesh.tets.size() - 1), 0.0);
    };
    graded.forEachFineTet(add);
    graded.forEachCoarseTet(add);
    double volume = 0.0;
    for (size_t t = 0; t < mesh.tets.size(); ++t) volume += signedTetVolume(mesh, t);
    // The box less a pyramid of height one half over each outer cube face.
    const double outerFaces = 6.0 * double(kCubes * kCubes);
    EXPECT_NEAR(volume, double(kCubes * kCubes * kCubes) - outerFaces / 6.0, 1e-6) << "grading " << grading;
    // Faces used once lie on the box's outer faces' pyramids: two vertices on the box.
    for (const auto& face : test::boundaryFaces(mesh)) {
      int onBox = 0;
      for (int32_t v : face) {
        const Eigen::Vector3d& x = mesh.vertices[size_t(v)];
        onBox += x.minCoeff() == 0.0 || x.maxCoeff() == double(kCubes);
      }
      EXPECT_GE(onBox, 2) << "grading " << grading;
    }
  }
}

// The coarse tets have all four vertices on the lattice, inside and unwarped, so they take a
// few fixed shapes (docs/choices.md, "Surface to tets"). Enumerating every way a face's edges
// can be split gives dihedral angles from arctan(1/sqrt(2)) = 35.26 to 125.26 degrees; every
// coarse tet must lie in that range for every grading, well inside the uniform stencils'
// bounds, which the tets near the surface keep.
TEST(GeometryGradedBccLattice, CoarseTetsKeepTheTransitionShapesAngles) {
  const Ball ball;
  const double low = std::atan(1.0 / std::sqrt(2.0)) * 180.0 / M_PI, high = 90.0 + low;
  for (int grading : {1, 2, 4}) {
    const GradedBccLattice graded(ball.lattice, ball.sign, grading);
    double lo = 180.0, hi = 0.0;
    int64_t count = 0;
    graded.forEachCoarseTet([&](const std::array<LatticePoint, 4>& p) {
      double a = 0.0, b = 0.0;
      tetDihedralRangeDegrees(ball.lattice.position(p[0]), ball.lattice.position(p[1]), ball.lattice.position(p[2]),
                              ball.lattice.position(p[3]), &a, &b);
      lo = std::min(lo, a), hi = std::max(hi, b);
      ++count;
    });
    std::printf("    grading %d: %lld coarse tets, dihedral angles %.2f-%.2f degrees\n", grading,
                static_cast<long long>(count), lo, hi);
    EXPECT_GT(count, 0);
    EXPECT_GE(lo, low - 1e-9) << "grading " << grading;
    EXPECT_LE(hi, high + 1e-9) << "grading " << grading;
  }
}

}  // namespace
}  // namespace vp
