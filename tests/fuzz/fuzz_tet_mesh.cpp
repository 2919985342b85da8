// Fuzz target: the tet-mesh readers (geometry/tet_mesh_file.h). The first byte picks the
// format: Gmsh .msh, legacy .vtk, or TetGen .node + .ele (the rest split at the first "#ele"
// line: before it the .node file, after it the .ele file).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input_file.h"
#include "geometry/tet_mesh_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const int format = data[0] % 3;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  std::string path;
  if (format == 0) {
    path = vp::fuzz::writeInput("mesh.msh", data + 1, size - 1);
  } else if (format == 1) {
    path = vp::fuzz::writeInput("mesh.vtk", data + 1, size - 1);
  } else {
    const size_t split = text.find("\n#ele\n");
    const std::string node = text.substr(0, split), ele = split == std::string::npos ? "" : text.substr(split + 6);
    path = vp::fuzz::writeInput("mesh.node", reinterpret_cast<const uint8_t*>(node.data()), node.size());
    vp::fuzz::writeInput("mesh.ele", reinterpret_cast<const uint8_t*>(ele.data()), ele.size());
  }
  vp::TetMesh mesh;
  vp::readTetMeshFile(path, &mesh);
  return 0;
}
