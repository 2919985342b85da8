// vpBoxTetMesh through the C ABI: the counts protocol, the mesh against the box it fills, the
// scene files' box, and refusals that name the field and write nothing.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "capi_test_support.h"

namespace {

struct BoxMesh {
  std::vector<float> vertices;
  std::vector<int32_t> tets;
};

BoxMesh makeMesh(vpVec3 size, std::array<int32_t, 3> cells, vpVec3 minCorner) {
  int32_t vertexCount = -1, tetCount = -1;
  EXPECT_VP_OK(vpBoxTetMesh(size, cells.data(), minCorner, nullptr, 0, nullptr, 0, &vertexCount, &tetCount));
  BoxMesh mesh;
  mesh.vertices.resize(3 * static_cast<size_t>(vertexCount));
  mesh.tets.resize(4 * static_cast<size_t>(tetCount));
  int32_t writtenVertices = -1, writtenTets = -1;
  EXPECT_VP_OK(vpBoxTetMesh(size, cells.data(), minCorner, mesh.vertices.data(), vertexCount, mesh.tets.data(),
                            tetCount, &writtenVertices, &writtenTets));
  EXPECT_EQ(writtenVertices, vertexCount);
  EXPECT_EQ(writtenTets, tetCount);
  return mesh;
}

double signedVolume(const BoxMesh& m, int32_t tet) {
  double p[4][3];
  for (int a = 0; a < 4; ++a)
    for (int k = 0; k < 3; ++k) p[a][k] = m.vertices[3 * m.tets[4 * tet + a] + k];
  double e[3][3];
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 3; ++k) e[a][k] = p[a + 1][k] - p[0][k];
  return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
          e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6.0;
}

TEST(CApiBoxTetMesh, CountsAloneWithNullOutputs) {
  const int32_t cells[3] = {3, 2, 1};
  int32_t vertexCount = -1, tetCount = -1;
  ASSERT_VP_OK(vpBoxTetMesh(vpVec3{3, 2, 1}, cells, vpVec3{0, 0, 0}, nullptr, 0, nullptr, 0, &vertexCount, &tetCount));
  EXPECT_EQ(vertexCount, 4 * 3 * 2);
  EXPECT_EQ(tetCount, 6 * 3 * 2 * 1);
}

TEST(CApiBoxTetMesh, LatticeVerticesAndPositiveTetsFillingTheBox) {
  const vpVec3 size{1.5f, 0.8f, 0.6f}, minCorner{-1.0f, 2.0f, 0.5f};
  const std::array<int32_t, 3> cells{3, 2, 2};
  const BoxMesh m = makeMesh(size, cells, minCorner);
  ASSERT_EQ(m.vertices.size(), 3u * 4 * 3 * 3);
  ASSERT_EQ(m.tets.size(), 4u * 6 * 3 * 2 * 2);
  // Vertex (i, j, k) at index i + 4 * (j + 3 * k), at minCorner + size * (i, j, k) / cells.
  const float lo[3] = {minCorner.x, minCorner.y, minCorner.z}, extent[3] = {size.x, size.y, size.z};
  for (int k = 0; k <= cells[2]; ++k)
    for (int j = 0; j <= cells[1]; ++j)
      for (int i = 0; i <= cells[0]; ++i) {
        const int index[3] = {i, j, k};
        const int v = i + 4 * (j + 3 * k);
        for (int a = 0; a < 3; ++a)
          EXPECT_FLOAT_EQ(m.vertices[3 * v + a], float(double(lo[a]) + double(extent[a]) * index[a] / cells[a]))
              << "vertex " << v << " axis " << a;
      }
  // Every tet is a sixth of a cell, positively oriented; together they make the box's volume.
  const double boxVolume = double(size.x) * size.y * size.z;
  const double tetVolume = boxVolume / (6.0 * cells[0] * cells[1] * cells[2]);
  const int32_t tetCount = static_cast<int32_t>(m.tets.size() / 4);
  double total = 0.0;
  for (int32_t t = 0; t < tetCount; ++t) {
    const double volume = signedVolume(m, t);
    EXPECT_NEAR(volume, tetVolume, 1e-5 * tetVolume) << "tet " << t;
    total += volume;
  }
  EXPECT_NEAR(total, boxVolume, 1e-6 * boxVolume);
  // Conforming: each face is shared by two tets except the boundary's, 2 triangles per cell face
  // on the surface.
  std::map<std::array<int32_t, 3>, int> faces;
  for (int32_t t = 0; t < tetCount; ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int32_t, 3> f;
      for (int a = 0, n = 0; a < 4; ++a)
        if (a != skip) f[n++] = m.tets[4 * t + a];
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  int boundary = 0;
  for (const auto& [face, uses] : faces) {
    EXPECT_LE(uses, 2);
    boundary += uses == 1;
  }
  EXPECT_EQ(boundary, 4 * (cells[0] * cells[1] + cells[1] * cells[2] + cells[2] * cells[0]));
}

TEST(CApiBoxTetMesh, SameMeshAsASceneFilesBox) {
  // tiny_world.json's "block": cells [2, 1, 1], size [0.4, 0.2, 0.2], centred at (1.5, 0.5, 0).
  ScopedWorld w;
  ASSERT_VP_OK(vpWorldLoadScene(w.id, VP_TEST_DATA_DIR "/scenes/tiny_world.json"));
  vpDeformableId block{};
  ASSERT_VP_OK(vpWorldFindDeformable(w.id, "block", &block));
  int32_t nodes = 0;
  ASSERT_VP_OK(vpDeformableGetNodeCount(block, &nodes));
  std::vector<float> scene(3 * static_cast<size_t>(nodes));
  ASSERT_VP_OK(vpDeformableGetPositions(block, scene.data(), nodes));
  const BoxMesh m = makeMesh(vpVec3{0.4f, 0.2f, 0.2f}, {2, 1, 1}, vpVec3{1.3f, 0.4f, -0.1f});
  ASSERT_EQ(m.vertices.size(), scene.size());
  for (size_t i = 0; i < scene.size(); ++i) EXPECT_NEAR(m.vertices[i], scene[i], 1e-6f) << "coordinate " << i;
}

TEST(CApiBoxTetMesh, ArraysMakeADeformable) {
  const BoxMesh m = makeMesh(vpVec3{1, 1, 1}, {2, 2, 2}, vpVec3{-0.5f, 1, -0.5f});
  ScopedWorld w;
  vpDeformableDef def = vpDefaultDeformableDef();
  def.vertices = m.vertices.data();
  def.vertexCount = static_cast<int32_t>(m.vertices.size() / 3);
  def.tets = m.tets.data();
  def.tetCount = static_cast<int32_t>(m.tets.size() / 4);
  vpDeformableId id{};
  ASSERT_VP_OK(vpDeformableCreate(w.id, &def, &id));
  int32_t nodes = 0;
  ASSERT_VP_OK(vpDeformableGetNodeCount(id, &nodes));
  EXPECT_EQ(nodes, 27);
}

TEST(CApiBoxTetMesh, TooSmallCapacitySetsTheCountsAndWritesNothing) {
  const int32_t cells[3] = {1, 1, 1};
  struct Case {
    int32_t vertexCapacity, tetCapacity;
    const char* message;
  };
  for (const Case& c : {Case{7, 6, "vertexCapacity = 7: the box mesh has 8 vertices"},
                        Case{8, 5, "tetCapacity = 5: the box mesh has 6 tets"}}) {
    std::vector<float> vertices(3 * 8, -7.0f);
    std::vector<int32_t> tets(4 * 6, -7);
    int32_t vertexCount = -1, tetCount = -1;
    EXPECT_EQ(vpBoxTetMesh(vpVec3{1, 1, 1}, cells, vpVec3{0, 0, 0}, vertices.data(), c.vertexCapacity, tets.data(),
                           c.tetCapacity, &vertexCount, &tetCount),
              vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains(c.message)) << vpGetLastError();
    EXPECT_EQ(vertexCount, 8);
    EXPECT_EQ(tetCount, 6);
    for (float v : vertices) EXPECT_EQ(v, -7.0f);
    for (int32_t t : tets) EXPECT_EQ(t, -7);
  }
}

TEST(CApiBoxTetMesh, BadArgumentsAreNamedAndChangeNothing) {
  const float nan = std::nanf("");
  struct Case {
    vpVec3 size;
    std::array<int32_t, 3> cells;
    vpVec3 minCorner;
    int32_t vertexCapacity;
    bool nullVertices;
    const char* message;
  };
  const Case cases[] = {
      {{1, 1, 1}, {2, 0, 2}, {0, 0, 0}, 27, false, "cells[1] = 0: must be in [1, 512]"},
      {{1, 1, 1}, {513, 1, 1}, {0, 0, 0}, 27, false, "cells[0] = 513: must be in [1, 512]"},
      {{1, 1, 1}, {2, 2, -3}, {0, 0, 0}, 27, false, "cells[2] = -3"},
      {{1, 1, 1}, {512, 512, 9}, {0, 0, 0}, 27, false, "cells = (512, 512, 9): 2359296 cells, at most 2097152"},
      {{1, -1, 1}, {2, 2, 2}, {0, 0, 0}, 27, false, "size.y = -1: must be in"},
      {{1, 1, nan}, {2, 2, 2}, {0, 0, 0}, 27, false, "size.z = nan"},
      {{0, 1, 1}, {2, 2, 2}, {0, 0, 0}, 27, false, "size.x = 0"},
      {{1, 1, 1}, {2, 2, 2}, {nan, 0, 0}, 27, false, "minCorner = (nan, 0, 0)"},
      {{1, 1, 1}, {2, 2, 2}, {1e6f, 0, 0}, 27, false, "minCorner + size = (1e+06"},
      {{1, 1, 1}, {2, 2, 2}, {0, 0, 0}, -1, false, "vertexCapacity = -1: must be >= 0"},
      {{1, 1, 1}, {2, 2, 2}, {0, 0, 0}, 27, true, "outVertices is NULL with vertexCapacity = 27"},
  };
  for (const Case& c : cases) {
    std::vector<float> vertices(3 * 27, -7.0f);
    std::vector<int32_t> tets(4 * 48, -7);
    int32_t vertexCount = -1, tetCount = -1;
    EXPECT_EQ(vpBoxTetMesh(c.size, c.cells.data(), c.minCorner, c.nullVertices ? nullptr : vertices.data(),
                           c.vertexCapacity, tets.data(), 48, &vertexCount, &tetCount),
              vpStatus_InvalidArgument)
        << c.message;
    EXPECT_TRUE(lastErrorContains(c.message)) << "expected '" << c.message << "', got '" << vpGetLastError() << "'";
    EXPECT_EQ(vertexCount, -1) << c.message;
    EXPECT_EQ(tetCount, -1) << c.message;
    for (float v : vertices) ASSERT_EQ(v, -7.0f) << c.message;
    for (int32_t t : tets) ASSERT_EQ(t, -7) << c.message;
  }
  int32_t count = -1;
  EXPECT_EQ(vpBoxTetMesh(vpVec3{1, 1, 1}, nullptr, vpVec3{0, 0, 0}, nullptr, 0, nullptr, 0, &count, &count),
            vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("cells is NULL")) << vpGetLastError();
  EXPECT_EQ(count, -1);
}

}  // namespace
