// The sample host's exports read back: it runs volphys_host on a small scene with a smoke
// plume and a liquid tank (no budget, one worker: the same steps as this process takes),
// reads each frame's .vdb with OpenVDB and .vti by its layout, and compares them with the
// fields vpFluidGetField gives after the same steps; collider meshes go through assimp's
// importer against vpColliderGetShapeMesh.
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <openvdb/openvdb.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "volphys/volphys.h"

namespace fs = std::filesystem;

namespace {

constexpr int kFrames = 3;
const char* const kScene = VP_TEST_DATA_DIR "/scenes/fluid_tank.json";

// Runs the host with the export options after the common ones, its output in OUT/host.log; the
// exit code.
int runHost(const fs::path& out, const std::string& options) {
  fs::remove_all(out);
  fs::create_directories(out);
  const std::string command = std::string(VP_HOST_EXE) + " --scene " + kScene + " --frames " +
                              std::to_string(kFrames) + " --budget 0 --workers 1 --snapshot-every 0 --quiet --out " +
                              out.string() + " " + options + " > " + (out / "host.log").string() + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Field {
  std::string name;
  std::vector<float> values;
  float background = 0.0f;
  bool levelSet = false;
};

struct FluidFrame {
  std::string name;
  int32_t n[3] = {0, 0, 0};
  vpVec3 origin{};
  float h = 0.0f;
  std::vector<Field> fields;
  int64_t index(int i, int j, int k) const { return i + int64_t(n[0]) * (j + int64_t(n[1]) * k); }
};

// The scene stepped as the host steps it; after each frame, every fluid's fields.
class SteppedScene {
 public:
  SteppedScene() {
    vpWorldDef def = vpDefaultWorldDef();
    def.workerCount = 1;
    EXPECT_EQ(vpWorldCreate(&def, &world_), vpStatus_Ok) << vpGetLastError();
    EXPECT_EQ(vpWorldLoadScene(world_, kScene), vpStatus_Ok) << vpGetLastError();
    EXPECT_EQ(vpWorldSetFrameBudget(world_, 0.0f), vpStatus_Ok);
  }
  ~SteppedScene() { vpWorldDestroy(world_); }
  vpWorldId world() const { return world_; }

  void step() { ASSERT_EQ(vpWorldStep(world_, static_cast<float>(1.0 / 60.0)), vpStatus_Ok) << vpGetLastError(); }

  std::vector<FluidFrame> fluids() const {
    int32_t count = 0;
    EXPECT_EQ(vpWorldGetFluidCount(world_, &count), vpStatus_Ok);
    std::vector<vpFluidId> ids(static_cast<size_t>(count));
    EXPECT_EQ(vpWorldGetFluids(world_, ids.data(), count, &count), vpStatus_Ok);
    std::vector<FluidFrame> frames;
    for (vpFluidId id : ids) {
      FluidFrame f;
      char name[64];
      int32_t length = 0;
      EXPECT_EQ(vpFluidGetName(id, name, sizeof name, &length), vpStatus_Ok);
      f.name = name;
      EXPECT_EQ(vpFluidGetResolution(id, &f.n[0], &f.n[1], &f.n[2]), vpStatus_Ok);
      EXPECT_EQ(vpFluidGetDomain(id, &f.origin, &f.h), vpStatus_Ok);
      vpFluidKind kind;
      EXPECT_EQ(vpFluidGetKind(id, &kind), vpStatus_Ok);
      const int64_t cells = int64_t(f.n[0]) * f.n[1] * f.n[2];
      auto read = [&](const char* fieldName, vpFluidField field, float background, bool levelSet) {
        Field out{fieldName, std::vector<float>(static_cast<size_t>(cells)), background, levelSet};
        EXPECT_EQ(vpFluidGetField(id, field, out.values.data(), cells), vpStatus_Ok);
        f.fields.push_back(std::move(out));
      };
      if (kind == vpFluidKind_Liquid) {
        read("level_set", vpFluidField_LevelSet, 3.0f * f.h, true);
      } else {
        vpFluidParameters p{};
        p.structSize = sizeof p;
        EXPECT_EQ(vpFluidGetParameters(id, &p), vpStatus_Ok);
        read("density", vpFluidField_SmokeDensity, 0.0f, false);
        read("temperature", vpFluidField_Temperature, p.ambientTemperature, false);
      }
      frames.push_back(std::move(f));
    }
    return frames;
  }

 private:
  vpWorldId world_{};
};

std::string framePath(const fs::path& out, const std::string& fluid, int frame, const char* ext) {
  char name[128];
  std::snprintf(name, sizeof name, "%s_f%05d.%s", fluid.c_str(), frame, ext);
  return (out / "volumes" / name).string();
}

// The cells a sparse file keeps: a level set's narrow band, other fields' non-background cells.
bool stored(const Field& f, float v) { return f.levelSet ? std::fabs(v) < f.background : v != f.background; }

void expectVdbMatches(const FluidFrame& fluid, const std::string& path) {
  SCOPED_TRACE(path);
  openvdb::io::File file(path);
  ASSERT_NO_THROW(file.open());
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  ASSERT_EQ(grids->size(), fluid.fields.size());
  for (const Field& field : fluid.fields) {
    SCOPED_TRACE(field.name);
    openvdb::FloatGrid::Ptr grid;
    for (const auto& g : *grids)
      if (g->getName() == field.name) grid = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
    ASSERT_TRUE(grid) << "no FloatGrid named " << field.name;
    // Voxel (i, j, k) is cell (i, j, k): its centre at origin + h * (i + 1/2, ...).
    const openvdb::Vec3d voxel = grid->voxelSize();
    const openvdb::Vec3d centre0 = grid->indexToWorld(openvdb::Coord(0, 0, 0));
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(voxel[a], fluid.h, 1e-7);
    EXPECT_NEAR(centre0[0], fluid.origin.x + 0.5 * fluid.h, 1e-6);
    EXPECT_NEAR(centre0[1], fluid.origin.y + 0.5 * fluid.h, 1e-6);
    EXPECT_NEAR(centre0[2], fluid.origin.z + 0.5 * fluid.h, 1e-6);
    EXPECT_EQ(grid->getGridClass(), field.levelSet           ? openvdb::GRID_LEVEL_SET
                                    : field.name == "density" ? openvdb::GRID_FOG_VOLUME
                                                              : openvdb::GRID_UNKNOWN);
    EXPECT_FLOAT_EQ(grid->background(), field.background);

    openvdb::CoordBBox expectedBox;
    openvdb::Index64 expectedActive = 0;
    int wrong = 0;
    auto acc = grid->getConstAccessor();
    for (int k = 0; k < fluid.n[2]; ++k)
      for (int j = 0; j < fluid.n[1]; ++j)
        for (int i = 0; i < fluid.n[0]; ++i) {
          const float v = field.values[static_cast<size_t>(fluid.index(i, j, k))];
          const openvdb::Coord ijk(i, j, k);
          const bool keep = stored(field, v);
          // Beyond a level set's band: the band's edge value with the cell's sign.
          const float expected = keep || !field.levelSet ? v : std::copysign(field.background, v);
          if (keep) expectedBox.expand(ijk), ++expectedActive;
          if (acc.getValue(ijk) != expected || acc.isValueOn(ijk) != keep) {
            if (++wrong <= 5)
              ADD_FAILURE() << "cell " << ijk << ": vdb " << acc.getValue(ijk) << (acc.isValueOn(ijk) ? " on" : " off")
                            << ", field " << v;
          }
        }
    EXPECT_EQ(wrong, 0);
    EXPECT_EQ(grid->activeVoxelCount(), expectedActive);
    EXPECT_EQ(grid->evalActiveVoxelBoundingBox(), expectedBox);
    // Something to look at: smoke near the emitter, a liquid surface in the tank.
    if (field.name != "temperature") {
      EXPECT_GT(expectedActive, 0u);
    }
    // Outside the domain: the background (a level set's outside).
    EXPECT_EQ(acc.getValue(openvdb::Coord(-2, -2, -2)), field.background);
  }
}

// The .vti's header as text and its appended arrays by name, read by the layout the writer
// documents (UInt64 byte count before each array, raw Float32 values).
struct Vti {
  std::string header;
  std::vector<std::pair<std::string, std::vector<float>>> arrays;
};

Vti readVti(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  Vti vti;
  const size_t appended = bytes.find("<AppendedData encoding=\"raw\">");
  if (appended == std::string::npos) return vti;
  const size_t start = bytes.find('_', appended) + 1;
  vti.header = bytes.substr(0, appended);
  const std::regex array("<DataArray type=\"Float32\" Name=\"([a-z_]+)\" format=\"appended\" offset=\"([0-9]+)\"/>");
  for (std::sregex_iterator m(vti.header.begin(), vti.header.end(), array), end; m != end; ++m) {
    const size_t offset = start + std::stoull((*m)[2]);
    uint64_t count = 0;
    if (offset + sizeof count > bytes.size()) break;
    std::memcpy(&count, bytes.data() + offset, sizeof count);
    if (offset + sizeof count + count > bytes.size()) break;
    std::vector<float> values(count / sizeof(float));
    std::memcpy(values.data(), bytes.data() + offset + sizeof count, count);
    vti.arrays.emplace_back((*m)[1], std::move(values));
  }
  return vti;
}

void expectVtiMatches(const FluidFrame& fluid, const std::string& path) {
  SCOPED_TRACE(path);
  const Vti vti = readVti(path);
  char expected[512];
  std::snprintf(expected, sizeof expected, "WholeExtent=\"0 %d 0 %d 0 %d\" Origin=\"%.9g %.9g %.9g\" Spacing=\"%.9g %.9g %.9g\"",
                fluid.n[0], fluid.n[1], fluid.n[2], fluid.origin.x, fluid.origin.y, fluid.origin.z, fluid.h, fluid.h,
                fluid.h);
  EXPECT_NE(vti.header.find(expected), std::string::npos) << vti.header;
  EXPECT_NE(vti.header.find("<CellData"), std::string::npos);
  ASSERT_EQ(vti.arrays.size(), fluid.fields.size());
  for (size_t a = 0; a < fluid.fields.size(); ++a) {
    EXPECT_EQ(vti.arrays[a].first, fluid.fields[a].name);
    EXPECT_TRUE(vti.arrays[a].second == fluid.fields[a].values) << fluid.fields[a].name << " differs";
  }
}

}  // namespace

TEST(SampleHostExports, VdbGridsHoldTheFluidFields) {
  openvdb::initialize();
  const fs::path out = fs::path(VP_TEST_OUT_DIR) / "vdb_export";
  ASSERT_EQ(runHost(out, "--export-volumes vdb --export-every 1"), 0) << "see " << (out / "host.log").string();
  SteppedScene scene;
  for (int frame = 0; frame < kFrames; ++frame) {
    scene.step();
    const std::vector<FluidFrame> fluids = scene.fluids();
    ASSERT_EQ(fluids.size(), 2u);
    for (const FluidFrame& f : fluids) expectVdbMatches(f, framePath(out, f.name, frame, "vdb"));
  }
}

TEST(SampleHostExports, VtiArraysHoldTheFluidFields) {
  const fs::path out = fs::path(VP_TEST_OUT_DIR) / "vti_export";
  ASSERT_EQ(runHost(out, "--export-volumes vti --export-every 2"), 0) << "see " << (out / "host.log").string();
  SteppedScene scene;
  for (int frame = 0; frame < kFrames; ++frame) {
    scene.step();
    const bool exported = frame % 2 == 0 || frame == kFrames - 1;
    for (const FluidFrame& f : scene.fluids()) {
      EXPECT_EQ(fs::exists(framePath(out, f.name, frame, "vti")), exported) << f.name << " frame " << frame;
      if (exported) expectVtiMatches(f, framePath(out, f.name, frame, "vti"));
    }
  }
}

// Each collider's mesh, written once in its local frame, imported again by assimp: the shape's
// triangles corner by corner.
TEST(SampleHostExports, ColliderMeshesRoundTripThroughAssimp) {
  for (const char* format : {"ply", "obj"}) {
    SCOPED_TRACE(format);
    const fs::path out = fs::path(VP_TEST_OUT_DIR) / (std::string("collider_meshes_") + format);
    ASSERT_EQ(runHost(out, std::string("--export-every 5 --export-format ") + format), 0)
        << "see " << (out / "host.log").string();
    SteppedScene scene;
    for (const char* name : {"ground", "rock"}) {
      SCOPED_TRACE(name);
      vpColliderId id;
      ASSERT_EQ(vpWorldFindCollider(scene.world(), name, &id), vpStatus_Ok);
      int32_t nv = 0, nt = 0;
      ASSERT_EQ(vpColliderGetShapeMeshSize(id, &nv, &nt), vpStatus_Ok);
      std::vector<float> positions(3 * static_cast<size_t>(nv));
      std::vector<int32_t> triangles(3 * static_cast<size_t>(nt));
      ASSERT_EQ(vpColliderGetShapeMesh(id, positions.data(), nullptr, nv, triangles.data(), nt), vpStatus_Ok);

      Assimp::Importer importer;
      const aiScene* imported = importer.ReadFile((out / "meshes" / (std::string(name) + "." + format)).string(), 0);
      ASSERT_TRUE(imported && imported->mNumMeshes == 1) << importer.GetErrorString();
      const aiMesh* mesh = imported->mMeshes[0];
      ASSERT_EQ(mesh->mNumFaces, static_cast<unsigned>(nt));
      ASSERT_TRUE(mesh->HasNormals());
      double worst = 0.0;
      for (int32_t t = 0; t < nt; ++t)
        for (int c = 0; c < 3; ++c) {
          const aiVector3D& p = mesh->mVertices[mesh->mFaces[t].mIndices[c]];
          const float* q = &positions[3 * static_cast<size_t>(triangles[3 * t + c])];
          for (int a = 0; a < 3; ++a) worst = std::max(worst, double(std::fabs(p[a] - q[a])));
        }
      EXPECT_LT(worst, 1e-4) << "largest corner difference";
    }
  }
}
