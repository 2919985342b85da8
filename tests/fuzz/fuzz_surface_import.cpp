// Fuzz target: surface import (geometry/surface_mesh.h) as a deformable's surfaceFile or a
// mesh collider's meshFile reach it: assimp in its isolated child. The first byte picks the
// extension. What assimp does with the bytes is its business; this process must survive it
// and get a status back.
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.h"
#include "geometry/surface_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* const kExtensions[] = {"off", "ply", "obj", "stl", "dae"};
  const char* ext = kExtensions[data[0] % 5];
  const std::string path = vp::fuzz::writeInput(std::string("surface.") + ext, data + 1, size - 1);
  vp::SurfaceMesh mesh;
  vp::loadSurfaceMesh(path, &mesh);
  return 0;
}
