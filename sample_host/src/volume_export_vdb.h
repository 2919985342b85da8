/* Writes a fluid's grids (volume_grids.h) to an OpenVDB file, one FloatGrid per field, named
 * after it. C++ inside (OpenVDB has no C interface), C outside. */
#ifndef VP_SAMPLE_VOLUME_EXPORT_VDB_H
#define VP_SAMPLE_VOLUME_EXPORT_VDB_H

#include "volume_grids.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Voxel (i, j, k) holds cell (i, j, k): the transform scales by cellSize and translates by
 * origin + cellSize / 2, so a voxel's centre is its cell's centre and the voxel box is the
 * cell. Only the cells volumeGridStores keeps are active; a level set is of class level set,
 * its other cells inactive at -background inside and +background outside (pruned to tiles),
 * density is a fog volume. Returns 1 on success; on failure prints the reason on stderr. */
int volumeExportVdb(const VolumeGrids* volume, const char* path);

#ifdef __cplusplus
}
#endif

#endif
