// Where a deformable's meshes come from: arrays, a tet file, a closed surface file that is
// tetrahedralized (isosurface stuffing by default, or voxels), or a built-in box. Resolves the
// source into DeformableDesc.mesh and DeformableDesc.renderMesh (an explicit render mesh, the
// surface itself, or by default the tet mesh's boundary).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "deform/deformable_desc.h"

namespace vp {

// How a surface file becomes tets; the values are vpSurfaceMesher's.
enum class SurfaceMesher : int {
  Default = 0,   // Stuffing
  Stuffing = 1,  // geometry/isosurface_stuffing.h: keeps the volume, bounded dihedral angles
  Voxel = 2,     // geometry/voxel_tetrahedralizer.h: covers the surface, swells thin parts
};

struct DeformableMeshSource {
  std::optional<TetMesh> tets;             // arrays
  std::string tetFile;                     // .msh / .node / .ele / .vtk
  std::string surfaceFile;                 // closed surface -> tets, kept as render mesh
  int voxelResolution = 12;                // either mesher: cells along the longest axis
  // The finest surface lattice a deformable may ask for: the tets of a finer one take longer
  // to build (and memory by the gigabyte) than a frame could ever step; a finer simulation
  // mesh comes in as a tetFile.
  static constexpr int kMaxVoxelResolution = 48;
  SurfaceMesher surfaceMesher = SurfaceMesher::Default;
  int meshGrading = 0;  // stuffing: levels of coarsening inside (isosurface_stuffing.h grading)
  std::optional<std::array<int, 3>> boxCells;  // built-in box: cells and size
  Vec3 boxSize{1.0, 1.0, 1.0};
  std::optional<SurfaceMesh> renderMesh;   // explicit render mesh (arrays or renderFile)
  std::string renderFile;
};

// Messages name the vpDeformableDef / scene fields (tetFile, surfaceFile, ...). A surfaceMesher
// outside the enum is InvalidArgument whatever the source.
Status resolveDeformableMesh(const DeformableMeshSource& source, DeformableDesc* desc);

}  // namespace vp
