// Faces a closed mesh covers whole or not at all, classified for a whole box at once
// (fluid/solids/mesh_face_classes.h): every face the classes decide has exactly the coverage the
// exact path gives it, most faces of a body's box are decided, and the fractions a box update
// computes with them match the exact path's face by face.
#include <gtest/gtest.h>

#include <memory>

#include "fluid/solids/face_fraction_field.h"
#include "fluid/solids/mesh_face_classes.h"
#include "geometry_test_shapes.h"

namespace vp {
namespace {

// A torus (a hole through it: rows that cross the surface four times) as a deforming surface,
// placed off the grid's lattice, in a 24^3 grid of 1/16.
struct TorusInAGrid {
  PreparedCollider torus;
  FaceFractionField field;
  TorusInAGrid() {
    const SurfaceMesh s = test::torus(0.45, 0.17, 48, 24);
    Array<Eigen::Vector3d> vertices;
    for (const Eigen::Vector3d& v : s.vertices) vertices.push_back(v + Eigen::Vector3d(0.751, 0.733, 0.727));
    Array<Eigen::Vector3i> triangles;
    for (const auto& t : s.triangles) triangles.emplace_back(t[0], t[1], t[2]);
    EXPECT_EQ(prepareDeformingSurface(vertices, triangles, &torus), Status::Ok) << lastError();
    MacGridSpec spec;
    spec.nx = spec.ny = spec.nz = 24;
    spec.h = 1.0 / 16.0;
    EXPECT_EQ(initFaceFractionField(spec, &field), Status::Ok);
  }
};

TEST(MeshFaceClasses, DecidedFacesHaveTheExactCoverageAndMostAreDecided) {
  TorusInAGrid t;
  MeshFaceClasses classes;
  classifyMeshFaces(t.torus, t.field, t.torus.bounds, &classes);
  int64_t decided = 0, inside = 0, total = 0;
  for (int a = 0; a < 3; ++a) {
    const FaceBox& r = classes.boxes[a];
    forEachFaceOf(r, 0, r.faces(), [&](int i, int j, int k) {
      ++total;
      const FaceClass c = classes.at(a, i, j, k);
      if (c == FaceClass::Touched) return;
      ++decided;
      inside += c == FaceClass::Inside;
      const double exact = coveredFraction(t.torus, t.field.face(a, i, j, k));
      EXPECT_NEAR(exact, c == FaceClass::Inside ? 1.0 : 0.0, 1e-12) << "axis " << a << " face " << i << " " << j << " " << k;
    });
  }
  EXPECT_GT(inside, 0);
  EXPECT_GT(decided, total / 2) << decided << " of " << total;
}

TEST(MeshFaceClasses, AMeshThatIsNotClosedLeavesEveryFaceToTheExactPath) {
  TorusInAGrid t;
  t.torus.triangles.pop_back();
  MeshFaceClasses classes;
  classifyMeshFaces(t.torus, t.field, t.torus.bounds, &classes);
  for (int a = 0; a < 3; ++a)
    for (uint8_t c : classes.classes[a]) ASSERT_EQ(c, static_cast<uint8_t>(FaceClass::Touched));
}

TEST(MeshFaceClasses, FractionsMatchTheExactCoverageFaceByFace) {
  TorusInAGrid t;
  const PreparedCollider* colliders[] = {&t.torus};
  ASSERT_EQ(computeFaceFractions(colliders, 1, &t.field), Status::Ok) << lastError();
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = t.field.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const double exact = 1.0 - coveredFraction(t.torus, t.field.face(a, i, j, k));
          ASSERT_NEAR(t.field.open[a][t.field.faceIndex(a, i, j, k)], exact, 1e-12) << a << " " << i << " " << j << " " << k;
        }
  }
}

}  // namespace
}  // namespace vp
