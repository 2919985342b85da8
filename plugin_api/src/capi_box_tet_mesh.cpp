// vpBoxTetMesh: the box mesher of scene files' "box" deformables, for hosts that build a
// deformable from arrays (one mesher for scenes and the API).
#include <array>

#include "capi_convert.h"
#include "core/physical_limits.h"
#include "geometry/box_tet_mesh.h"

using namespace vp;
using namespace vp::capi;

namespace {

// An output array and its capacity: NULL asks for nothing, and then the capacity must be 0.
Status checkOutput(const char* arrayName, const void* array, const char* capacityName, int32_t capacity) {
  if (capacity < 0) return fail(Status::InvalidArgument, "%s = %d: must be >= 0", capacityName, capacity);
  if (!array && capacity > 0)
    return fail(Status::InvalidArgument, "%s is NULL with %s = %d", arrayName, capacityName, capacity);
  return Status::Ok;
}

}  // namespace

extern "C" {

vpStatus vpBoxTetMesh(vpVec3 size, const int32_t cells[3], vpVec3 minCorner, float* outVertices,
                      int32_t vertexCapacity, int32_t* outTets, int32_t tetCapacity, int32_t* outVertexCount,
                      int32_t* outTetCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(cells);
    const std::array<int, 3> c{cells[0], cells[1], cells[2]};
    const Vec3 extent = toVec3(size), lowCorner = toVec3(minCorner);
    VP_TRY(checkBoxTetMeshArgs(c, extent));
    VP_TRY(checkPosition("minCorner", lowCorner));
    VP_TRY(checkPosition("minCorner + size", lowCorner + extent));
    VP_TRY(checkOutput("outVertices", outVertices, "vertexCapacity", vertexCapacity));
    VP_TRY(checkOutput("outTets", outTets, "tetCapacity", tetCapacity));
    // The checked limits keep both counts far inside int32.
    const int32_t vertexCount = (c[0] + 1) * (c[1] + 1) * (c[2] + 1), tetCount = 6 * c[0] * c[1] * c[2];
    auto reportCounts = [&] {
      if (outVertexCount) *outVertexCount = vertexCount;
      if (outTetCount) *outTetCount = tetCount;
    };
    if (outVertices && vertexCapacity < vertexCount) {
      reportCounts();
      return fail(Status::InvalidArgument, "vertexCapacity = %d: the box mesh has %d vertices", vertexCapacity,
                  vertexCount);
    }
    if (outTets && tetCapacity < tetCount) {
      reportCounts();
      return fail(Status::InvalidArgument, "tetCapacity = %d: the box mesh has %d tets", tetCapacity, tetCount);
    }
    if (outVertices || outTets) {
      const TetMesh mesh = makeBoxTetMesh(c, extent, lowCorner);
      if (outVertices)
        for (int32_t i = 0; i < vertexCount; ++i)
          for (int k = 0; k < 3; ++k) outVertices[3 * i + k] = static_cast<float>(mesh.vertices[i][k]);
      if (outTets)
        for (int32_t t = 0; t < tetCount; ++t)
          for (int k = 0; k < 4; ++k) outTets[4 * t + k] = mesh.tets[t][k];
    }
    reportCounts();
    return Status::Ok;
  });
}

}  // extern "C"
