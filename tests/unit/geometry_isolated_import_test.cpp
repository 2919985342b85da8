// Surface files are imported where a crash, hang or exhaustion of the importer cannot reach
// the host (geometry/isolated_import.h); only regular files are read; a surface that is not
// closed is named by its first open edge (geometry/closed_surface.h).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <csignal>
#include <string>
#include <thread>

#include "core/regular_file.h"
#include "geometry/closed_surface.h"
#include "geometry/isolated_import.h"
#include "geometry/surface_mesh.h"
#include "geometry/tet_mesh_file.h"
#include "geometry_test_files.h"
#include "geometry_test_shapes.h"

namespace vp {
namespace {

bool errorContains(const std::string& part) { return std::string(lastError()).find(part) != std::string::npos; }

Status crashingImporter(const std::string&, SurfaceMesh*) {
  std::raise(SIGSEGV);
  return Status::Ok;
}

Status hangingImporter(const std::string&, SurfaceMesh*) {
  for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
}

Status failingImporter(const std::string& path, SurfaceMesh*) {
  return fail(Status::IoError, "file '%s': the importer's own error", path.c_str());
}

Status boxImporter(const std::string&, SurfaceMesh* out) {
  *out = test::boxSurface(Eigen::Vector3d(-0.1, 0.2, 0.3), Eigen::Vector3d(1.0 / 3.0, 0.7, 2.5));
  return Status::Ok;
}

TEST(IsolatedImport, AMeshComesBackBitForBit) {
  SurfaceMesh direct, isolated;
  ASSERT_EQ(boxImporter("", &direct), Status::Ok);
  ASSERT_EQ(importIsolated("box", &boxImporter, ImportLimits{}, &isolated), Status::Ok) << lastError();
  ASSERT_EQ(isolated.vertices.size(), direct.vertices.size());
  ASSERT_EQ(isolated.triangles, direct.triangles);
  for (size_t v = 0; v < direct.vertices.size(); ++v) EXPECT_EQ(isolated.vertices[v], direct.vertices[v]);
}

TEST(IsolatedImport, TheImportersErrorComesBackWithItsStatus) {
  SurfaceMesh out;
  EXPECT_EQ(importIsolated("some.obj", &failingImporter, ImportLimits{}, &out), Status::IoError);
  EXPECT_TRUE(errorContains("file 'some.obj': the importer's own error")) << lastError();
}

TEST(IsolatedImport, ACrashIsAParseErrorAndTheHostLives) {
  SurfaceMesh out;
  out.vertices.emplace_back(1, 2, 3);
  EXPECT_EQ(importIsolated("bad.ply", &crashingImporter, ImportLimits{}, &out), Status::ParseError);
  EXPECT_TRUE(errorContains("file 'bad.ply': the importer crashed on it (signal 11")) << lastError();
  EXPECT_EQ(out.vertices.size(), 1u);  // unchanged
}

TEST(IsolatedImport, AHangIsStoppedAtTheTimeLimit) {
  ImportLimits limits;
  limits.wallSeconds = 0.3;
  SurfaceMesh out;
  EXPECT_EQ(importIsolated("slow.dae", &hangingImporter, limits, &out), Status::ParseError);
  EXPECT_TRUE(errorContains("file 'slow.dae': the importer did not finish within 0.3 s")) << lastError();
}

// Inputs that crash or exhaust assimp 5.2.5 in-process (found by mutating small OFF and PLY
// files): through loadSurfaceMesh each is an error, and this process goes on.
TEST(IsolatedImport, AssimpCrashersAreErrors) {
  for (const char* name : {"segv_header_after_faces.off", "abort_vertex_count.off", "segv_face_list.ply"}) {
    SurfaceMesh out;
    const std::string path = std::string(VP_TEST_DATA_DIR "/hostile/") + name;
    EXPECT_EQ(loadSurfaceMesh(path, &out), Status::ParseError) << name << ": " << lastError();
    EXPECT_TRUE(errorContains("the importer crashed on it")) << lastError();
  }
  // A header that promises 10^8 faces: assimp allocates and loops for minutes in-process.
  ImportLimits limits;
  limits.wallSeconds = 1.0;
  SurfaceMesh out;
  const Status s = importIsolated(VP_TEST_DATA_DIR "/hostile/endless_element_count.ply", &importSurfaceMeshWithAssimp,
                                  limits, &out);
  EXPECT_TRUE(s == Status::ParseError || s == Status::OutOfMemory) << statusName(s) << ": " << lastError();
}

TEST(RegularFile, ReadersRefuseAFifoInsteadOfBlocking) {
  test::TempDir dir;
  const std::string fifo = dir.file("mesh.obj");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  SurfaceMesh surface;
  EXPECT_EQ(loadSurfaceMesh(fifo, &surface), Status::IoError);
  EXPECT_TRUE(errorContains("is a FIFO; only regular files are read")) << lastError();
  const std::string tetFifo = dir.file("mesh.msh");
  ASSERT_EQ(::mkfifo(tetFifo.c_str(), 0600), 0);
  TetMesh tets;
  EXPECT_EQ(readTetMeshFile(tetFifo, &tets), Status::IoError);
  EXPECT_TRUE(errorContains("is a FIFO")) << lastError();
  EXPECT_EQ(checkRegularFile(dir.file("")), Status::IoError);
  EXPECT_TRUE(errorContains("is a directory")) << lastError();
  EXPECT_EQ(checkRegularFile(dir.file("missing")), Status::IoError);
  EXPECT_TRUE(errorContains("cannot be opened (No such file or directory)")) << lastError();
}

TEST(ClosedSurface, ABoxIsClosedEvenWithItsCornersSplit) {
  SurfaceMesh box = test::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  EXPECT_EQ(checkClosedSurface(box.vertices, box.triangles, "surface"), Status::Ok) << lastError();
  // An importer splits vertices along texture seams: the same corner under two indices.
  SurfaceMesh seams = box;
  for (auto& t : seams.triangles) {
    seams.vertices.push_back(seams.vertices[t[0]]);
    t[0] = int32_t(seams.vertices.size() - 1);
  }
  EXPECT_EQ(checkClosedSurface(seams.vertices, seams.triangles, "surface"), Status::Ok) << lastError();
}

TEST(ClosedSurface, HolesSheetsAndFlipsAreNamedByAnEdge) {
  SurfaceMesh box = test::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  SurfaceMesh holed = box;
  holed.triangles.pop_back();
  EXPECT_EQ(checkClosedSurface(holed.vertices, holed.triangles, "surface"), Status::InvalidArgument);
  EXPECT_TRUE(errorContains("surface: is not closed: edge (")) << lastError();
  EXPECT_TRUE(errorContains("borders a hole")) << lastError();
  SurfaceMesh flipped = box;
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_EQ(checkClosedSurface(flipped.vertices, flipped.triangles, "surface"), Status::InvalidArgument);
  EXPECT_TRUE(errorContains("is not closed")) << lastError();
  SurfaceMesh quad;
  quad.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(checkClosedSurface(quad.vertices, quad.triangles, "surface"), Status::InvalidArgument);
  EXPECT_TRUE(errorContains("borders a hole")) << lastError();
}

}  // namespace
}  // namespace vp
