// Collider shapes as triangle meshes for the host to draw or export.
#include "capi_convert.h"
#include "capi_copy_out.h"
#include "collide/shape_display_mesh.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

vpStatus vpColliderGetShapeMeshSize(vpColliderId id, int32_t* outVertexCount, int32_t* outTriangleCount) {
  return guarded(__func__, [&] {
    WorldLease w;
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
    WorldLease w;
    Collider* c;
    VP_TRY(resolveCollider(id, &w, &c));
    const ShapeDisplayMesh m = buildShapeDisplayMesh(c->desc().shape);
    return copyMeshOut("shape mesh", m.positions, m.normals, m.triangles, outPositions, outNormals, vertexCapacity,
                       outTriangles, triangleCapacity);
  });
}
