// Collider shapes as triangle meshes for the host to draw or export.
#include <cstring>

#include "capi_convert.h"
#include "collide/shape_display_mesh.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

vpStatus vpColliderGetShapeMeshSize(vpColliderId id, int32_t* outVertexCount, int32_t* outTriangleCount) {
  return guarded(__func__, [&] {
    World* w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    const ShapeDisplayMesh m = buildShapeDisplayMesh(c->desc().shape);
    if (outVertexCount) *outVertexCount = static_cast<int32_t>(m.positions.size());
    if (outTriangleCount) *outTriangleCount = static_cast<int32_t>(m.triangles.size());
    return Status::Ok;
  });
}

vpStatus vpColliderGetShapeMesh(vpColliderId id, float* outPositions, float* outNormals, int32_t vertexCapacity,
                                int32_t* outTriangles, int32_t triangleCapacity) {
  return guarded(__func__, [&] {
    World* w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    const ShapeDisplayMesh m = buildShapeDisplayMesh(c->desc().shape);
    const int32_t nv = static_cast<int32_t>(m.positions.size()), nt = static_cast<int32_t>(m.triangles.size());
    if ((outPositions || outNormals) && vertexCapacity < nv)
      return fail(Status::InvalidArgument, "vertexCapacity = %d: the shape mesh has %d vertices", vertexCapacity, nv);
    if (outTriangles && triangleCapacity < nt)
      return fail(Status::InvalidArgument, "triangleCapacity = %d: the shape mesh has %d triangles", triangleCapacity,
                  nt);
    for (int32_t i = 0; i < nv; ++i)
      for (int k = 0; k < 3; ++k) {
        if (outPositions) outPositions[3 * i + k] = static_cast<float>(m.positions[i][k]);
        if (outNormals) outNormals[3 * i + k] = static_cast<float>(m.normals[i][k]);
      }
    if (outTriangles) std::memcpy(outTriangles, m.triangles.data(), sizeof(int32_t) * 3 * static_cast<size_t>(nt));
    return Status::Ok;
  });
}
