// Where a deformable's meshes come from: arrays, a tet file, a closed surface file that is
// voxel-tetrahedralized, or a built-in box. Resolves the source into DeformableDesc.mesh and
// DeformableDesc.renderMesh (an explicit render mesh, the voxelized surface itself, or by
// default the tet mesh's boundary).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "deform/deformable_desc.h"

namespace vp {

struct DeformableMeshSource {
  std::optional<TetMesh> tets;             // arrays
  std::string tetFile;                     // .msh / .node / .ele / .vtk
  std::string surfaceFile;                 // closed surface -> voxel tets, kept as render mesh
  int voxelResolution = 12;
  std::optional<std::array<int, 3>> boxCells;  // built-in box: cells and size
  Vec3 boxSize{1.0, 1.0, 1.0};
  std::optional<SurfaceMesh> renderMesh;   // explicit render mesh (arrays or renderFile)
  std::string renderFile;
};

// Messages name the vpDeformableDef / scene fields (tetFile, surfaceFile, ...).
Status resolveDeformableMesh(const DeformableMeshSource& source, DeformableDesc* desc);

}  // namespace vp
