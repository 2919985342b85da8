// loadSurfaceMesh through assimp: triangulation, merging of meshes with node transforms,
// clear errors.
#include "geometry/surface_mesh.h"

#include "geometry_test_files.h"
#include "geometry_test_shapes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace vp {
namespace {

std::string base64(const std::string& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t chunk = static_cast<uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) chunk |= static_cast<uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) chunk |= static_cast<uint8_t>(bytes[i + 2]);
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

TEST(GeometrySurfaceMesh, ObjRoundTripAndTriangulation) {
  test::TempDir dir;
  const SurfaceMesh sphere = test::icosphere(2, 1.0);
  const std::string path = dir.file("sphere.obj");
  ASSERT_EQ(writeSurfaceMeshObj(sphere, path), Status::Ok) << lastError();
  SurfaceMesh loaded;
  ASSERT_EQ(loadSurfaceMesh(path, &loaded), Status::Ok) << lastError();
  EXPECT_EQ(loaded.triangles.size(), sphere.triangles.size());
  EXPECT_EQ(loaded.vertices.size(), sphere.vertices.size());  // JoinIdenticalVertices welds the OBJ corners
  // assimp stores positions as float: volume agrees to float round-off (~1e-7 relative).
  EXPECT_NEAR(test::enclosedVolume(loaded), test::enclosedVolume(sphere), 1e-6);

  // A quad and a pentagon are triangulated (2 + 3 triangles); a line element is dropped.
  const std::string poly = dir.write("poly.obj",
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
                                     "f 1 2 3 4\nf 1 2 3 5 4\nl 1 3\n");
  ASSERT_EQ(loadSurfaceMesh(poly, &loaded), Status::Ok) << lastError();
  EXPECT_EQ(loaded.triangles.size(), 5u);
}

TEST(GeometrySurfaceMesh, MergesMeshesWithNodeTransforms) {
  // One triangle mesh instanced by two nodes: node A translates by (10, 0, 0); its child B
  // scales by 2 (so B's world transform is translate * scale).
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t indices[3] = {0, 1, 2};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
  buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
  buffer.append(2, '\0');  // pad to 4 bytes
  const std::string gltf = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [10, 0, 0], "children": [1]}, {"mesh": 0, "scale": [2, 2, 2]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,)" +
                           base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
})";
  test::TempDir dir;
  SurfaceMesh loaded;
  ASSERT_EQ(loadSurfaceMesh(dir.write("two.gltf", gltf), &loaded), Status::Ok) << lastError();
  ASSERT_EQ(loaded.triangles.size(), 2u);
  ASSERT_EQ(loaded.vertices.size(), 6u);
  Eigen::Vector3d lo = loaded.vertices[0], hi = lo;
  for (const auto& v : loaded.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // Both instances start at x = 10; the scaled one reaches 12.
  EXPECT_EQ(lo, Eigen::Vector3d(10, 0, 0));
  EXPECT_EQ(hi, Eigen::Vector3d(12, 2, 0));
  for (const auto& tri : loaded.triangles)
    for (int32_t v : tri) EXPECT_LT(v, 6);
}

TEST(GeometrySurfaceMesh, Errors) {
  test::TempDir dir;
  SurfaceMesh out;
  out.vertices.emplace_back(1, 2, 3);
  EXPECT_EQ(loadSurfaceMesh(dir.file("missing.obj"), &out), Status::IoError);
  EXPECT_NE(std::string(lastError()).find("missing.obj"), std::string::npos) << lastError();
  EXPECT_EQ(loadSurfaceMesh(dir.write("points.obj", "v 0 0 0\nv 1 0 0\np 1 2\n"), &out), Status::ParseError);
  EXPECT_NE(std::string(lastError()).find("no triangles"), std::string::npos) << lastError();
  EXPECT_EQ(loadSurfaceMesh(dir.write("junk.xyzzy", "this is not a mesh\n"), &out), Status::ParseError);
  EXPECT_NE(std::string(lastError()).find("junk.xyzzy"), std::string::npos) << lastError();
  ASSERT_EQ(out.vertices.size(), 1u);  // unchanged
  EXPECT_TRUE(out.triangles.empty());
}

}  // namespace
}  // namespace vp
