#include "deform/deformable_mesh_source.h"

#include "geometry/box_tet_mesh.h"
#include "geometry/closed_surface.h"
#include "geometry/isosurface_stuffing.h"
#include "geometry/tet_mesh_boundary.h"
#include "geometry/tet_mesh_file.h"
#include "geometry/voxel_tetrahedralizer.h"

namespace vp {
namespace {

Status checkSurfaceMesher(SurfaceMesher mesher) {
  const int value = static_cast<int>(mesher);
  if (value < static_cast<int>(SurfaceMesher::Default) || value > static_cast<int>(SurfaceMesher::Voxel))
    return fail(Status::InvalidArgument, "surfaceMesher = %d: must be 0 (default), 1 (stuffing) or 2 (voxel)", value);
  return Status::Ok;
}

Status tetrahedralizeSurface(const SurfaceMesh& surface, const DeformableMeshSource& source, TetMesh* mesh) {
  if (source.surfaceMesher == SurfaceMesher::Voxel) return tetrahedralizeVoxels(surface, source.voxelResolution, mesh);
  VP_TRY(tetrahedralizeByStuffing(surface, source.voxelResolution, mesh, nullptr, StuffingBoundary::KeepVolume,
                                  source.meshGrading));
  if (mesh->tets.empty())
    return fail(Status::InvalidArgument,
                "surfaceMesher = stuffing: no lattice vertex at voxelResolution = %d is inside the surface (thinner "
                "than a cell); raise voxelResolution or use the voxel mesher",
                source.voxelResolution);
  return Status::Ok;
}

}  // namespace

Status resolveDeformableMesh(const DeformableMeshSource& source, DeformableDesc* desc) {
  VP_TRY(checkSurfaceMesher(source.surfaceMesher));
  if (source.meshGrading < 0 || source.meshGrading > kMaxStuffingGrading)
    return fail(Status::InvalidArgument, "meshGrading = %d: must be in [0, %d]", source.meshGrading,
                kMaxStuffingGrading);
  const int sources = int(source.tets.has_value()) + int(!source.tetFile.empty()) + int(!source.surfaceFile.empty()) +
                      int(source.boxCells.has_value());
  if (sources != 1)
    return fail(Status::InvalidArgument,
                "mesh source: give exactly one of vertices/tets, tetFile, surfaceFile or box (got %d)", sources);
  TetMesh mesh;
  std::optional<SurfaceMesh> render = source.renderMesh;
  if (source.tets) {
    mesh = *source.tets;
  } else if (!source.tetFile.empty()) {
    Status s = readTetMeshFile(source.tetFile, &mesh);
    if (!ok(s)) return addErrorContext(s, "tetFile");
  } else if (!source.surfaceFile.empty()) {
    if (source.voxelResolution < 1 || source.voxelResolution > DeformableMeshSource::kMaxVoxelResolution)
      return fail(Status::InvalidArgument, "voxelResolution = %d: must be in [1, %d]", source.voxelResolution,
                  DeformableMeshSource::kMaxVoxelResolution);
    SurfaceMesh surface;
    Status s = loadSurfaceMesh(source.surfaceFile, &surface);
    if (!ok(s)) return addErrorContext(s, "surfaceFile");
    s = checkClosedSurface(surface.vertices, surface.triangles, "surface");
    if (!ok(s)) return addErrorContext(s, "surfaceFile '" + source.surfaceFile + "'");
    s = tetrahedralizeSurface(surface, source, &mesh);
    if (!ok(s)) return addErrorContext(s, "surfaceFile");
    if (!render) render = std::move(surface);
  } else {
    const Status s = checkBoxTetMeshArgs(*source.boxCells, source.boxSize);
    if (!ok(s)) return addErrorContext(s, "box");
    mesh = makeBoxTetMesh(*source.boxCells, source.boxSize, -0.5 * source.boxSize);  // centred on the origin
  }
  if (!source.renderFile.empty()) {
    if (source.renderMesh)
      return fail(Status::InvalidArgument, "renderFile: give either render arrays or renderFile, not both");
    SurfaceMesh loaded;
    Status s = loadSurfaceMesh(source.renderFile, &loaded);
    if (!ok(s)) return addErrorContext(s, "renderFile");
    render = std::move(loaded);
  }
  desc->mesh = std::move(mesh);
  desc->renderMesh = std::move(render);  // empty: the body uses the tet boundary
  return Status::Ok;
}

}  // namespace vp
