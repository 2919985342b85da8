// vpColliderGetShapeMesh: every shape gives a closed, outward-wound mesh whose enclosed
// volume matches the shape's (divergence theorem), so hosts can draw and export it as is.
#include <cmath>
#include <vector>

#include "capi_test_support.h"

namespace {

struct Mesh {
  std::vector<float> positions, normals;
  std::vector<int32_t> triangles;
};

Mesh shapeMesh(vpColliderId id) {
  Mesh m;
  int32_t nv = 0, nt = 0;
  EXPECT_VP_OK(vpColliderGetShapeMeshSize(id, &nv, &nt));
  m.positions.resize(3 * size_t(nv));
  m.normals.resize(3 * size_t(nv));
  m.triangles.resize(3 * size_t(nt));
  EXPECT_VP_OK(vpColliderGetShapeMesh(id, m.positions.data(), m.normals.data(), nv, m.triangles.data(), nt));
  return m;
}

// Signed volume: positive when every triangle is counter-clockwise seen from outside.
double enclosedVolume(const Mesh& m) {
  double v = 0;
  for (size_t t = 0; t < m.triangles.size(); t += 3) {
    const float* a = &m.positions[3 * size_t(m.triangles[t])];
    const float* b = &m.positions[3 * size_t(m.triangles[t + 1])];
    const float* c = &m.positions[3 * size_t(m.triangles[t + 2])];
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
  }
  return v;
}

vpColliderId create(vpWorldId world, vpShapeDef shape) {
  vpColliderDef def = vpDefaultColliderDef();
  def.shape = shape;
  def.pose.position.y = 3.0f;  // the mesh is local: the pose must not show in it
  vpColliderId id{};
  EXPECT_VP_OK(vpColliderCreate(world, &def, &id));
  return id;
}

TEST(CapiColliderMesh, ClosedShapesEncloseTheirVolume) {
  ScopedWorld w;
  const double pi = 3.14159265358979;
  vpShapeDef sphere = vpDefaultShapeDef();
  sphere.radius = 0.5f;
  vpShapeDef box = vpDefaultShapeDef();
  box.type = vpShapeType_Box;
  box.halfExtents = {0.5f, 1.0f, 1.5f};
  vpShapeDef capsule = vpDefaultShapeDef();
  capsule.type = vpShapeType_Capsule;
  capsule.radius = 0.25f;
  capsule.halfHeight = 0.5f;
  vpShapeDef cylinder = capsule;
  cylinder.type = vpShapeType_Cylinder;
  const float octahedron[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0.1f, 0.1f, 0.1f};
  vpShapeDef hull = vpDefaultShapeDef();
  hull.type = vpShapeType_ConvexHull;
  hull.points = octahedron;
  hull.pointCount = 7;  // the last point is inside and must not show

  struct Case {
    const char* name;
    vpShapeDef shape;
    double volume, tolerance;
  } cases[] = {
      {"sphere", sphere, 4.0 / 3.0 * pi * 0.125, 0.05},
      {"box", box, 8 * 0.5 * 1.0 * 1.5, 1e-6},
      {"capsule", capsule, 4.0 / 3.0 * pi * 0.015625 + pi * 0.0625 * 1.0, 0.05},
      {"cylinder", cylinder, pi * 0.0625 * 1.0, 0.03},
      {"convex hull", hull, 4.0 / 3.0, 1e-6},
  };
  for (const Case& c : cases) {
    const Mesh m = shapeMesh(create(w.id, c.shape));
    ASSERT_FALSE(m.triangles.empty()) << c.name;
    EXPECT_NEAR(enclosedVolume(m), c.volume, c.tolerance * c.volume) << c.name;
    for (size_t i = 0; i < m.normals.size(); i += 3)
      EXPECT_NEAR(std::sqrt(m.normals[i] * m.normals[i] + m.normals[i + 1] * m.normals[i + 1] +
                            m.normals[i + 2] * m.normals[i + 2]),
                  1.0, 1e-4)
          << c.name;
    for (int32_t index : m.triangles) ASSERT_LT(size_t(index), m.positions.size() / 3) << c.name;
  }
}

TEST(CapiColliderMesh, PlaneIsASquareOnThePlaneFacingItsNormal) {
  ScopedWorld w;
  vpShapeDef plane = vpDefaultShapeDef();
  plane.type = vpShapeType_Plane;
  plane.normal = {0, 2, 0};  // not unit: the library normalizes it
  plane.offset = 0.5f;
  const Mesh m = shapeMesh(create(w.id, plane));
  ASSERT_EQ(m.triangles.size(), 6u);
  for (size_t i = 0; i < m.positions.size(); i += 3) {
    EXPECT_NEAR(m.positions[i + 1], 0.5f, 1e-5);
    EXPECT_NEAR(std::abs(m.positions[i]), 10.0f, 1e-4);
    EXPECT_NEAR(m.normals[i + 1], 1.0f, 1e-6);
  }
}

TEST(CapiColliderMesh, SmallCapacityAndBadIdsAreErrors) {
  ScopedWorld w;
  const vpColliderId id = create(w.id, vpDefaultShapeDef());
  int32_t nv = 0, nt = 0;
  ASSERT_VP_OK(vpColliderGetShapeMeshSize(id, &nv, &nt));
  std::vector<float> xyz(3 * size_t(nv));
  EXPECT_EQ(vpColliderGetShapeMesh(id, xyz.data(), nullptr, nv - 1, nullptr, 0), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("vertexCapacity")) << vpGetLastError();
  EXPECT_VP_OK(vpColliderGetShapeMesh(id, xyz.data(), nullptr, nv, nullptr, 0));  // triangles not wanted
  EXPECT_EQ(vpColliderGetShapeMeshSize(vpColliderId{}, &nv, &nt), vpStatus_InvalidId);
}

}  // namespace
