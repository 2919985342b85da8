#include "volume_export_vdb.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include <cstdio>
#include <exception>

namespace {

openvdb::FloatGrid::Ptr makeGrid(const VolumeGrids& v, const VolumeGrid& field) {
  auto grid = openvdb::FloatGrid::create(field.background);
  grid->setName(field.name);
  const double h = v.cellSize;
  auto transform = openvdb::math::Transform::createLinearTransform(h);
  transform->postTranslate(openvdb::Vec3d(v.origin[0] + 0.5 * h, v.origin[1] + 0.5 * h, v.origin[2] + 0.5 * h));
  grid->setTransform(transform);
  const bool levelSet = field.gridClass == VolumeGridClass_LevelSet;
  grid->setGridClass(levelSet                                          ? openvdb::GRID_LEVEL_SET
                     : field.gridClass == VolumeGridClass_FogVolume ? openvdb::GRID_FOG_VOLUME
                                                                    : openvdb::GRID_UNKNOWN);
  auto acc = grid->getAccessor();
  for (int32_t k = 0; k < v.nz; ++k)
    for (int32_t j = 0; j < v.ny; ++j)
      for (int32_t i = 0; i < v.nx; ++i) {
        const float value = field.values[i + static_cast<int64_t>(v.nx) * (j + static_cast<int64_t>(v.ny) * k)];
        const openvdb::Coord ijk(i, j, k);
        if (volumeGridStores(&field, value))
          acc.setValueOn(ijk, value);
        else if (levelSet && value < 0.0f)
          acc.setValueOff(ijk, -field.background);  // inside the liquid, beyond the band
      }
  // Inactive interior voxels collapse into -background tiles, the rest into +background.
  if (levelSet)
    openvdb::tools::pruneLevelSet(grid->tree());
  else
    openvdb::tools::pruneInactive(grid->tree());
  return grid;
}

}  // namespace

extern "C" int volumeExportVdb(const VolumeGrids* volume, const char* path) {
  try {
    openvdb::initialize();
    openvdb::GridPtrVec grids;
    for (int g = 0; g < volume->gridCount; ++g) grids.push_back(makeGrid(*volume, volume->grids[g]));
    openvdb::io::File file(path);
    file.write(grids);
    file.close();
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "volume export: cannot write '%s': %s\n", path, e.what());
    return 0;
  }
}
