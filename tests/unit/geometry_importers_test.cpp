// The volumetric importers: every valid format gives the same mesh; malformed input gives
// the right status and a message naming the file and line; nothing crashes.
#include "geometry/gmsh_reader.h"
#include "geometry/tet_mesh_file.h"
#include "geometry/tetgen_reader.h"
#include "geometry/vtk_reader.h"

#include "geometry_test_files.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace vp {
namespace {

const std::string kData = std::string(VP_TEST_DATA_DIR) + "/geometry/";

// The cube [0,1]^3 split into 6 tets around the diagonal 0-7, as written in every data file.
TetMesh expectedCube() {
  TetMesh mesh;
  for (int i = 0; i < 8; ++i) mesh.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  mesh.tets = {{{0, 1, 3, 7}}, {{0, 1, 5, 7}}, {{0, 2, 3, 7}},
               {{0, 2, 6, 7}}, {{0, 4, 5, 7}}, {{0, 4, 6, 7}}};
  return mesh;
}

void expectSameMesh(const TetMesh& expected, const TetMesh& actual) {
  ASSERT_EQ(expected.vertices.size(), actual.vertices.size());
  for (size_t i = 0; i < expected.vertices.size(); ++i)
    EXPECT_EQ(expected.vertices[i], actual.vertices[i]) << "vertex " << i;  // exact: small decimals
  EXPECT_EQ(expected.tets, actual.tets);
}

using Reader = std::function<Status(const std::string&, TetMesh*)>;

// Expects `status` and that the message names the file and, when line > 0, that line.
void expectError(const std::string& path, const Reader& read, Status status, int line,
                 const std::string& fragment = "") {
  TetMesh out;
  out.vertices.emplace_back(7, 7, 7);  // must survive a failed read
  Status got = read(path, &out);
  EXPECT_EQ(statusName(status), std::string(statusName(got))) << lastError();
  const std::string message = lastError();
  // The message names the file (for tetgen it may be the .node or the .ele of the pair).
  std::string stem = path.substr(path.find_last_of('/') + 1);
  stem = stem.substr(0, stem.find('.'));
  EXPECT_NE(message.find("/" + stem + "."), std::string::npos) << message;
  if (line > 0) {
    EXPECT_NE(message.find("line " + std::to_string(line) + ":"), std::string::npos) << message;
  }
  if (!fragment.empty()) {
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
  ASSERT_EQ(out.vertices.size(), 1u);
  EXPECT_TRUE(out.tets.empty());
}

// --- valid files --------------------------------------------------------------------------

TEST(GeometryImporters, EveryFormatGivesTheSameCube) {
  const TetMesh expected = expectedCube();
  const char* files[] = {"cube_v22.msh", "cube_v41.msh", "cube0.node", "cube0.ele", "cube0",
                         "cube1.node",   "cube.vtk"};
  for (const char* name : files) {
    SCOPED_TRACE(name);
    TetMesh mesh;
    Status s = std::string(name).find(".msh") != std::string::npos ? readGmsh(kData + name, &mesh)
               : std::string(name).find(".vtk") != std::string::npos ? readVtk(kData + name, &mesh)
                                                                     : readTetGen(kData + name, &mesh);
    ASSERT_EQ(s, Status::Ok) << lastError();
    expectSameMesh(expected, mesh);
  }
}

TEST(GeometryImporters, ReadTetMeshFileDispatchesAndRepairsOrientation) {
  for (const char* name : {"cube_v22.msh", "cube_v41.msh", "cube1.ele", "cube.vtk"}) {
    SCOPED_TRACE(name);
    TetMesh mesh;
    TetMeshRepairReport report;
    ASSERT_EQ(readTetMeshFile(kData + name, &mesh, &report), Status::Ok) << lastError();
    // Half of the 6 tets around a diagonal are negatively oriented by construction.
    EXPECT_EQ(report.invertedTetsFixed, 3);
    EXPECT_EQ(report.unusedVerticesRemoved, 0);
    EXPECT_NEAR(totalVolume(mesh), 1.0, 1e-15);
    for (size_t t = 0; t < mesh.tets.size(); ++t) EXPECT_GT(signedTetVolume(mesh, t), 0.0);
  }
  TetMesh mesh;
  EXPECT_EQ(readTetMeshFile(kData + "cube.obj", &mesh), Status::Unsupported);
  EXPECT_EQ(readTetMeshFile(kData + "missing.msh", &mesh), Status::IoError);
}

TEST(GeometryImporters, VtkVersion51OffsetsLayout) {
  test::TempDir dir;
  std::string path = dir.write("v51.vtk",
                               "# vtk DataFile Version 5.1\n"
                               "vtk output\n"
                               "ASCII\n"
                               "DATASET UNSTRUCTURED_GRID\n"
                               "FIELD FieldData 1\n"
                               "TIME 1 1 double\n"
                               "0.5\n"
                               "POINTS 8 float\n"
                               "0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1\n"
                               "METADATA\n"
                               "INFORMATION 0\n"
                               "\n"
                               "CELLS 8 27\n"
                               "OFFSETS vtktypeint64\n"
                               "0 3 7 11 15 19 23 27\n"
                               "CONNECTIVITY vtktypeint64\n"
                               "0 1 3 0 1 3 7 0 1 5 7 0 2 3 7 0 2 6 7 0 4 5 7 0 4 6 7\n"
                               "CELL_TYPES 7\n"
                               "5 10 10 10 10 10 10\n");
  TetMesh mesh;
  ASSERT_EQ(readVtk(path, &mesh), Status::Ok) << lastError();
  expectSameMesh(expectedCube(), mesh);
}

TEST(GeometryImporters, TetGenTenNodeTetsKeepCorners) {
  test::TempDir dir;
  std::string node = "11 3 0 0\n";
  for (int i = 0; i < 11; ++i) node += std::to_string(i) + " " + std::to_string(i % 2) + " " +
                                       std::to_string((i / 2) % 2) + " " + std::to_string(i / 4) + "\n";
  dir.write("quad.node", node);
  dir.write("quad.ele", "1 10 0\n0 0 1 2 4 5 6 7 8 9 10\n");
  TetMesh mesh;
  ASSERT_EQ(readTetGen(dir.file("quad"), &mesh), Status::Ok) << lastError();
  ASSERT_EQ(mesh.tets.size(), 1u);
  EXPECT_EQ(mesh.tets[0], (std::array<int32_t, 4>{{0, 1, 2, 4}}));
}

// --- malformed gmsh ----------------------------------------------------------------------

std::string cubeV22() { return test::readWholeFile(kData + "cube_v22.msh"); }
std::string cubeV41() { return test::readWholeFile(kData + "cube_v41.msh"); }

std::string replaceOnce(std::string text, const std::string& from, const std::string& to) {
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(GeometryImporters, GmshMalformed) {
  test::TempDir dir;
  // Line numbers refer to cube_v22.msh: $Nodes at line 8, its count at 9, nodes 10..17,
  // $EndNodes 18, $Elements 19, count 20, elements 21..29.
  expectError(dir.write("trunc.msh", cubeV22().substr(0, cubeV22().find("21 0 0 1"))), readGmsh,
              Status::ParseError, 9, "truncated");
  expectError(dir.write("trunc2.msh", cubeV22().substr(0, cubeV22().find("9 4 2"))), readGmsh,
              Status::ParseError, 29, "element tag (an integer), got end of file");
  expectError(dir.write("garbage.msh", replaceOnce(cubeV22(), "13 1 1 0", "13 1 x1 0")), readGmsh,
              Status::ParseError, 13, "'x1'");
  expectError(dir.write("count.msh", replaceOnce(cubeV22(), "$Nodes\n8", "$Nodes\n9")), readGmsh,
              Status::ParseError, 18, "got '$EndNodes'");
  expectError(dir.write("fewer.msh", replaceOnce(cubeV22(), "$Elements\n9", "$Elements\n10")), readGmsh,
              Status::ParseError, 30, "element 10 of 10");
  expectError(dir.write("huge.msh", replaceOnce(cubeV22(), "$Nodes\n8", "$Nodes\n2000000000")), readGmsh,
              Status::ParseError, 9, "cannot fit");
  expectError(dir.write("huge64.msh", replaceOnce(cubeV22(), "$Nodes\n8", "$Nodes\n99999999999999999999")),
              readGmsh, Status::ParseError, 9, "integer");
  expectError(dir.write("undef.msh", replaceOnce(cubeV22(), "3 21 55 89", "3 21 56 89")), readGmsh,
              Status::ParseError, 29, "node tag 56");
  expectError(dir.write("dup.msh", replaceOnce(cubeV22(), "8 0 1 0", "5 0 1 0")), readGmsh, Status::ParseError,
              12, "defined twice");
  expectError(dir.write("extra.msh", replaceOnce(cubeV22(), "4 4 2 1 1 3 5 13 89", "4 4 2 1 1 3 5 13 89 3")),
              readGmsh, Status::ParseError, 24, "end of line");
  expectError(dir.write("binary.msh", "$MeshFormat\n4.1 1 8\n\x01\0\0\0\n$EndMeshFormat\n"), readGmsh,
              Status::Unsupported, 0, "binary");
  expectError(dir.write("v40.msh", replaceOnce(cubeV41(), "4.1 0 8", "4 0 8")), readGmsh, Status::Unsupported, 0,
              "version 4");
  expectError(dir.write("noformat.msh", "$Nodes\n0\n$EndNodes\n"), readGmsh, Status::ParseError, 1,
              "$MeshFormat");
  expectError(dir.write("notets.msh",
                        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                        "$EndNodes\n$Elements\n1\n1 2 0 1 2 3\n$EndElements\n"),
              readGmsh, Status::ParseError, 0, "no 4-node tetrahedra");
  expectError(dir.write("unclosed.msh", replaceOnce(cubeV22(), "$EndPhysicalNames", "")), readGmsh,
              Status::ParseError, 4, "$EndPhysicalNames");
  expectError(dir.file("does_not_exist.msh"), readGmsh, Status::IoError, 0, "cannot be opened");
  // 4.1 specific: block sizes disagreeing with the header.
  expectError(dir.write("blocks.msh", replaceOnce(cubeV41(), "2 8 3 89", "2 9 3 89")), readGmsh,
              Status::ParseError, 0, "declared 9");
  expectError(dir.write("eblocks.msh", replaceOnce(cubeV41(), "3 1 4 6", "3 1 4 7")), readGmsh,
              Status::ParseError, 0, "more than the 8 elements");
}

// --- malformed tetgen --------------------------------------------------------------------

TEST(GeometryImporters, TetGenMalformed) {
  test::TempDir dir;
  const std::string node0 = test::readWholeFile(kData + "cube0.node");
  const std::string ele0 = test::readWholeFile(kData + "cube0.ele");
  auto writePair = [&](const std::string& base, const std::string& node, const std::string& ele) {
    dir.write(base + ".node", node);
    dir.write(base + ".ele", ele);
    return dir.file(base + ".node");
  };
  expectError(writePair("range", node0, replaceOnce(ele0, "5  0 4 6 7", "5  0 4 6 8")), readTetGen,
              Status::ParseError, 7, "node index 8");
  expectError(writePair("garbage", replaceOnce(node0, "3  1 1 0", "3  1 1 zero"), ele0), readTetGen,
              Status::ParseError, 6, "'zero'");
  expectError(writePair("base", replaceOnce(node0, "0  0 0 0", "2  0 0 0"), ele0), readTetGen,
              Status::ParseError, 3, "0 or 1");
  expectError(writePair("gap", replaceOnce(node0, "4  0 0 1", "9  0 0 1"), ele0), readTetGen,
              Status::ParseError, 7, "consecutive");
  expectError(writePair("attr", replaceOnce(node0, "5  1 0 1  0.5  1", "5  1 0 1  0.5"), ele0), readTetGen,
              Status::ParseError, 8, "boundary marker (an integer), got end of line");
  expectError(writePair("huge", replaceOnce(node0, "8 3 1 1", "1000000000 3 1 1"), ele0), readTetGen,
              Status::ParseError, 2, "cannot fit");
  expectError(writePair("trunc", node0, ele0.substr(0, ele0.size() - 12)), readTetGen, Status::ParseError, 7,
              "got end of line");
  expectError(writePair("more", node0, replaceOnce(ele0, "6 4 1", "5 4 1")), readTetGen, Status::ParseError, 7,
              "end of file after the 5 records");
  expectError(writePair("dim", replaceOnce(node0, "8 3 1 1", "8 2 1 1"), ele0), readTetGen, Status::ParseError,
              2, "dimension must be 3");
  dir.write("lonely.node", node0);
  expectError(dir.file("lonely.node"), readTetGen, Status::IoError, 0, "lonely.ele");
}

// --- malformed vtk -----------------------------------------------------------------------

TEST(GeometryImporters, VtkMalformed) {
  test::TempDir dir;
  const std::string vtk = test::readWholeFile(kData + "cube.vtk");
  // Lines of cube.vtk: POINTS 5, coordinates 6..8, CELLS 9, cells 10..16, CELL_TYPES 17.
  expectError(dir.write("binary.vtk", replaceOnce(vtk, "ASCII", "BINARY")), readVtk, Status::Unsupported, 0,
              "binary");
  expectError(dir.write("poly.vtk", replaceOnce(vtk, "UNSTRUCTURED_GRID", "POLYDATA")), readVtk,
              Status::Unsupported, 4, "POLYDATA");
  expectError(dir.write("trunc.vtk", vtk.substr(0, vtk.find("4 0 2 6 7"))), readVtk, Status::ParseError, 9,
              "truncated");
  expectError(dir.write("three.vtk", replaceOnce(vtk, "4 0 4 6 7", "3 0 4 6 7")), readVtk, Status::ParseError,
              16, "");
  expectError(dir.write("size.vtk", replaceOnce(vtk, "CELLS 7 34", "CELLS 7 35")), readVtk, Status::ParseError,
              0, "CELLS size says 35");
  expectError(dir.write("types.vtk", replaceOnce(vtk, "CELL_TYPES 7\n5\n", "CELL_TYPES 6\n")), readVtk,
              Status::ParseError, 17, "6 types but CELLS has 7");
  expectError(dir.write("range.vtk", replaceOnce(vtk, "4 0 4 6 7", "4 0 4 6 8")), readVtk, Status::ParseError,
              16, "point 8");
  expectError(dir.write("huge.vtk", replaceOnce(vtk, "POINTS 8 double", "POINTS 900000000 double")), readVtk,
              Status::ParseError, 5, "cannot fit");
  expectError(dir.write("ptype.vtk", replaceOnce(vtk, "POINTS 8 double", "POINTS 8 string")), readVtk,
              Status::ParseError, 5, "float or double");
  expectError(dir.write("garbage.vtk", replaceOnce(vtk, "1 1 0  0 0 1", "1 1 0  0 0 #")), readVtk,
              Status::ParseError, 7, "'#'");
  expectError(dir.write("header.vtk", "hello\n"), readVtk, Status::ParseError, 1, "header");
}

// Every prefix of every valid file and a sweep of single-byte corruptions must give a
// status, never a crash (run under ASan/UBSan this is a small deterministic fuzz test).
TEST(GeometryImporters, TruncationAndCorruptionNeverCrash) {
  test::TempDir dir;
  struct Case { const char* name; Reader read; };
  const Case cases[] = {{"cube_v22.msh", readGmsh}, {"cube_v41.msh", readGmsh}, {"cube.vtk", readVtk},
                        {"cube0.node", readTetGen}};
  const char garbage[] = {'\0', '-', '9', 'e', '$', '\n', ' ', '#', '\xff'};
  for (const Case& c : cases) {
    const std::string text = test::readWholeFile(kData + c.name);
    const std::string ext = std::string(c.name).substr(std::string(c.name).find('.'));
    if (ext == ".node") dir.write("f.ele", test::readWholeFile(kData + "cube0.ele"));
    int failures = 0;
    for (size_t cut = 0; cut < text.size(); ++cut) {
      TetMesh mesh;
      if (c.read(dir.write("f" + ext, text.substr(0, cut)), &mesh) != Status::Ok) ++failures;
    }
    for (size_t at = 0; at < text.size(); ++at) {
      std::string corrupted = text;
      corrupted[at] = garbage[at % sizeof garbage];
      TetMesh mesh;
      (void)c.read(dir.write("f" + ext, corrupted), &mesh);
    }
    // Most prefixes are incomplete files; only those cut after the last needed token read.
    EXPECT_GT(failures, static_cast<int>(text.size()) * 3 / 4) << c.name;
  }
}

}  // namespace
}  // namespace vp
