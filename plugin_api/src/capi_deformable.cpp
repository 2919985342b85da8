// Deformable volume actors: creation from vpDeformableDef, state access, constraints.
#include <cmath>

#include "capi_convert.h"
#include "capi_versioned_struct.h"
#include "capi_copy_out.h"
#include "deform/deformable_mesh_source.h"
#include "world_registry.h"

using namespace vp;
using namespace vp::capi;

static_assert(static_cast<int>(SurfaceMesher::Default) == vpSurfaceMesher_Default &&
                  static_cast<int>(SurfaceMesher::Stuffing) == vpSurfaceMesher_Stuffing &&
                  static_cast<int>(SurfaceMesher::Voxel) == vpSurfaceMesher_Voxel,
              "vp::SurfaceMesher and vpSurfaceMesher must match");
static_assert(static_cast<int>(SelfCollision::Auto) == vpSelfCollision_Auto &&
                  static_cast<int>(SelfCollision::Off) == vpSelfCollision_Off &&
                  static_cast<int>(SelfCollision::On) == vpSelfCollision_On,
              "vp::SelfCollision and vpSelfCollision must match");

namespace {

Status copyPoints(const char* field, const float* xyz, int32_t count, Array<Vec3>* out) {
  if (count <= 0 || count > (1 << 26))
    return fail(Status::InvalidArgument, "%sCount = %d: must be in [1, 2^26]", field, count);
  out->resize(static_cast<size_t>(count));
  for (int32_t i = 0; i < count; ++i) (*out)[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  return Status::Ok;
}

Status translateMeshSource(const vpDeformableDef& d, DeformableMeshSource* src) {
  if (d.vertices || d.tets) {
    if (!d.vertices || !d.tets)
      return fail(Status::InvalidArgument, "vertices/tets: both arrays are needed (got %p and %p)",
                  static_cast<const void*>(d.vertices), static_cast<const void*>(d.tets));
    TetMesh mesh;
    VP_TRY(copyPoints("vertex", d.vertices, d.vertexCount, &mesh.vertices));
    if (d.tetCount <= 0 || d.tetCount > (1 << 26))
      return fail(Status::InvalidArgument, "tetCount = %d: must be in [1, 2^26]", d.tetCount);
    mesh.tets.resize(static_cast<size_t>(d.tetCount));
    std::memcpy(mesh.tets.data(), d.tets, sizeof(int32_t) * 4 * static_cast<size_t>(d.tetCount));
    src->tets = std::move(mesh);
  }
  if (d.tetFile) src->tetFile = d.tetFile;
  if (d.surfaceFile) src->surfaceFile = d.surfaceFile;
  src->voxelResolution = d.voxelResolution;
  src->surfaceMesher = static_cast<SurfaceMesher>(d.surfaceMesher);  // resolveDeformableMesh checks the range
  src->meshGrading = d.meshGrading;                                   // and this one
  if (d.renderVertices || d.renderTriangles) {
    if (!d.renderVertices || !d.renderTriangles)
      return fail(Status::InvalidArgument, "renderVertices/renderTriangles: both arrays are needed");
    SurfaceMesh render;
    VP_TRY(copyPoints("renderVertex", d.renderVertices, d.renderVertexCount, &render.vertices));
    if (d.renderTriangleCount <= 0 || d.renderTriangleCount > (1 << 26))
      return fail(Status::InvalidArgument, "renderTriangleCount = %d: must be in [1, 2^26]", d.renderTriangleCount);
    render.triangles.resize(static_cast<size_t>(d.renderTriangleCount));
    std::memcpy(render.triangles.data(), d.renderTriangles, sizeof(int32_t) * 3 * size_t(d.renderTriangleCount));
    src->renderMesh = std::move(render);
  }
  return Status::Ok;
}

Status checkNodeArray(const int32_t* nodes, int32_t count) {
  if (count < 0) return fail(Status::InvalidArgument, "count = %d: must be >= 0", count);
  if (count > 0 && !nodes) return fail(Status::InvalidArgument, "nodes is NULL with count = %d", count);
  return Status::Ok;
}

// A host array of xyz per node, for every node of `d`, as doubles.
Status readNodeArray(const DeformableBody& d, const float* xyz, int32_t nodeCount, std::vector<double>* out) {
  if (nodeCount != d.nodeCount())
    return fail(Status::InvalidArgument, "nodeCount = %d: the actor has %d nodes", nodeCount, d.nodeCount());
  out->assign(xyz, xyz + 3 * static_cast<size_t>(nodeCount));
  return Status::Ok;
}

}  // namespace

extern "C" {

int vpDeformableIdIsNull(vpDeformableId id) { return id.index1 == 0; }

vpDeformableDef vpDefaultDeformableDef(void) {
  const DeformableDesc defaults;
  vpDeformableDef d{};
  d.structSize = sizeof(vpDeformableDef);
  d.degree = 1;
  d.voxelResolution = 12;
  d.pose.rotation.w = 1.0f;
  d.youngsModulus = static_cast<float>(defaults.material.youngsModulus);
  d.poissonRatio = static_cast<float>(defaults.material.poissonRatio);
  d.density = static_cast<float>(defaults.material.density);
  d.massDamping = static_cast<float>(defaults.material.massDamping);
  d.stiffnessDamping = static_cast<float>(defaults.material.stiffnessDamping);
  d.friction = static_cast<float>(defaults.material.friction);
  d.solverTolerance = static_cast<float>(defaults.solver.tolerance);
  d.solverMaxIterations = defaults.solver.maxIterations;
  d.targetResidual = static_cast<float>(defaults.solver.targetResidual);
  d.priority = defaults.priority;
  d.filter = toC(defaults.filter);
  d.surfaceMesher = static_cast<int32_t>(DeformableMeshSource{}.surfaceMesher);
  d.selfCollision = static_cast<int32_t>(defaults.selfCollision);
  d.meshGrading = DeformableMeshSource{}.meshGrading;
  return d;
}

vpStatus vpDeformableCreate(vpWorldId worldId, const vpDeformableDef* def, vpDeformableId* out) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(def);
    VP_REQUIRE_POINTER(out);
    WorldLease world;
    VP_TRY(resolveWorld(worldId, &world));
    vpDeformableDef d;  // the host's def, with an older header's missing fields at their defaults
    VP_TRY(readVersioned("vpDeformableDef", def, vpDefaultDeformableDef(), &d));
    DeformableMeshSource source;
    VP_TRY(translateMeshSource(d, &source));
    DeformableDesc desc;
    VP_TRY(resolveDeformableMesh(source, &desc));
    desc.degree = d.degree;
    desc.pose = toPose(d.pose);
    desc.linearVelocity = toVec3(d.linearVelocity);
    desc.material.youngsModulus = d.youngsModulus;
    desc.material.poissonRatio = d.poissonRatio;
    desc.material.density = d.density;
    desc.material.massDamping = d.massDamping;
    desc.material.stiffnessDamping = d.stiffnessDamping;
    desc.material.friction = d.friction;
    desc.solver.tolerance = d.solverTolerance;
    desc.solver.maxIterations = d.solverMaxIterations;
    desc.solver.targetResidual = d.targetResidual;
    desc.priority = d.priority;
    desc.filter = toFilter(d.filter);
    desc.selfCollision = static_cast<SelfCollision>(d.selfCollision);  // validateDeformableDesc checks the range
    desc.userData = d.userData;
    DeformableHandle h;
    VP_TRY(world->createDeformable(std::move(desc), &h));
    *out = makeDeformableId(worldId, h);
    return Status::Ok;
  });
}

vpStatus vpDeformableDestroy(vpDeformableId id) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    return w->destroyDeformable(handleOf(id));
  });
}

vpStatus vpDeformableIsValid(vpDeformableId id) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    return resolveDeformable(id, &w, &d);
  });
}

vpStatus vpDeformableGetNodeCount(vpDeformableId id, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    *outCount = d->nodeCount();
    return Status::Ok;
  });
}

static Status copyOut(const Array<double>& values, int32_t nodes, float* out, int32_t capacity) {
  if (!out) return fail(Status::InvalidArgument, "outXyz is NULL");
  if (capacity < nodes)
    return fail(Status::InvalidArgument, "capacity = %d: the actor has %d nodes", capacity, nodes);
  for (int64_t i = 0; i < 3 * static_cast<int64_t>(nodes); ++i) out[i] = static_cast<float>(values[i]);
  return Status::Ok;
}

vpStatus vpDeformableGetPositions(vpDeformableId id, float* outXyz, int32_t capacity) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    return copyOut(d->positions(), d->nodeCount(), outXyz, capacity);
  });
}

vpStatus vpDeformableGetVelocities(vpDeformableId id, float* outXyz, int32_t capacity) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    return copyOut(d->velocities(), d->nodeCount(), outXyz, capacity);
  });
}

vpStatus vpDeformableSetVelocities(vpDeformableId id, const float* xyz, int32_t nodeCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(xyz);
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    std::vector<double> v;
    VP_TRY(readNodeArray(*d, xyz, nodeCount, &v));
    return d->setVelocities(v.data(), static_cast<int64_t>(v.size()));
  });
}

vpStatus vpDeformableSetPositions(vpDeformableId id, const float* xyz, int32_t nodeCount, int32_t resetVelocities) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(xyz);
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    std::vector<double> x;
    VP_TRY(readNodeArray(*d, xyz, nodeCount, &x));
    VP_TRY(d->setPositions(x.data(), static_cast<int64_t>(x.size())));
    if (resetVelocities != 0) {
      std::fill(x.begin(), x.end(), 0.0);
      VP_TRY(d->setVelocities(x.data(), static_cast<int64_t>(x.size())));
    }
    d->updateRenderMesh(w->tasks());
    return Status::Ok;
  });
}

vpStatus vpDeformableApplyForce(vpDeformableId id, int32_t node, vpVec3 force) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    return d->applyForce(node, toVec3(force));
  });
}

vpStatus vpDeformableApplyImpulse(vpDeformableId id, int32_t node, vpVec3 impulse) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    return d->applyImpulse(node, toVec3(impulse));
  });
}

vpStatus vpDeformablePin(vpDeformableId id, const int32_t* nodes, int32_t count) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    VP_TRY(checkNodeArray(nodes, count));
    return d->setPinned(nodes, count, true);
  });
}

vpStatus vpDeformableUnpin(vpDeformableId id, const int32_t* nodes, int32_t count) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    VP_TRY(checkNodeArray(nodes, count));
    return d->setPinned(nodes, count, false);
  });
}

vpStatus vpDeformableAttach(vpDeformableId id, const int32_t* nodes, int32_t count, vpColliderId colliderId) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    VP_TRY(checkNodeArray(nodes, count));
    Collider* c;
    VP_TRY(resolveColliderIn(id.world, *w, colliderId, &c));
    const ColliderHandle ch = handleOf(colliderId);
    return d->attach(nodes, count, ch.index1, ch.generation, *c);
  });
}

vpStatus vpDeformableGetRenderMeshSize(vpDeformableId id, int32_t* outVertexCount, int32_t* outTriangleCount) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    if (outVertexCount) *outVertexCount = static_cast<int32_t>(d->renderPositions().size());
    if (outTriangleCount) *outTriangleCount = static_cast<int32_t>(d->renderMeshRest().triangles.size());
    return Status::Ok;
  });
}

vpStatus vpDeformableGetRenderMesh(vpDeformableId id, float* outPositions, float* outNormals, int32_t vertexCapacity,
                                   int32_t* outTriangles, int32_t triangleCapacity) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    return copyMeshOut("render mesh", d->renderPositions(), d->renderNormals(), d->renderMeshRest().triangles,
                       outPositions, outNormals, vertexCapacity, outTriangles, triangleCapacity);
  });
}

vpStatus vpDeformableSolveStatic(vpDeformableId id, int32_t maxIterations, float tolerance, int32_t* outIterations,
                                 float* outResidual) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    StaticSolveResult result;
    const Status s = w->solveDeformableStatic(handleOf(id), maxIterations, tolerance, &result);
    if (outIterations) *outIterations = result.iterations;
    if (outResidual) *outResidual = static_cast<float>(result.residual);
    return s;
  });
}

vpStatus vpDeformableGetMeshQuality(vpDeformableId id, float* outMinDihedralDegrees, float* outMaxDihedralDegrees,
                                    float* outTetVolume, float* outSurfaceVolume) {
  return guarded(__func__, [&] {
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    const TetMeshQuality& q = d->meshQuality();
    if (outMinDihedralDegrees) *outMinDihedralDegrees = static_cast<float>(q.minDihedralDegrees);
    if (outMaxDihedralDegrees) *outMaxDihedralDegrees = static_cast<float>(q.maxDihedralDegrees);
    if (outTetVolume) *outTetVolume = static_cast<float>(q.tetVolume);
    if (outSurfaceVolume) *outSurfaceVolume = static_cast<float>(q.surfaceVolume);
    return Status::Ok;
  });
}

vpStatus vpDeformableGetStats(vpDeformableId id, vpActorStats* outStats) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outStats);
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    vpActorStats stats = vpDefaultActorStats();
    stats.kind = vpActorKind_Deformable;
    stats.index1 = id.index1;
    for (const ActorStats& a : w->lastStats().actors)
      if (a.kind == ActorKind::Deformable && a.index1 == id.index1 && a.generation == handleOf(id).generation)
        fillActorStats(a, &stats);
    return writeVersioned("vpActorStats", stats, outStats);
  });
}

vpStatus vpWorldFindDeformable(vpWorldId id, const char* name, vpDeformableId* out) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(name);
    VP_REQUIRE_POINTER(out);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    DeformableHandle h;
    if (!w->findDeformable(name, &h))
      return fail(Status::InvalidArgument, "name = \"%s\": no deformable has this name", name);
    *out = makeDeformableId(id, h);
    return Status::Ok;
  });
}

vpStatus vpDeformableGetName(vpDeformableId id, char* buffer, int32_t capacity, int32_t* outLength) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outLength);
    WorldLease w;
    DeformableBody* d;
    VP_TRY(resolveDeformable(id, &w, &d));
    return copyStringOut(d->desc().name, buffer, capacity, outLength);
  });
}

}  // extern "C"

vpStatus vpWorldGetDeformableCount(vpWorldId id, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    *outCount = static_cast<int32_t>(w->deformableCount());
    return Status::Ok;
  });
}

vpStatus vpWorldGetDeformables(vpWorldId id, vpDeformableId* outIds, int32_t capacity, int32_t* outCount) {
  return guarded(__func__, [&] {
    VP_REQUIRE_POINTER(outCount);
    WorldLease w;
    VP_TRY(resolveWorld(id, &w));
    return copyIdsOut(w->deformableHandles(), [&](DeformableHandle h) { return makeDeformableId(id, h); }, outIds,
                      capacity, outCount);
  });
}
