/* A fluid's cell-centred fields as the volume exporters write them (volume_export_vdb.h,
 * volume_export_vti.h): smoke as "density" and "temperature", a liquid as "level_set".
 * Values are x fastest, cell (i, j, k) at i + nx * (j + ny * k), and cell (i, j, k) is the box
 * origin + cellSize * [i, i + 1] x [j, j + 1] x [k, k + 1] (its sample is at the box's centre). */
#ifndef VP_SAMPLE_VOLUME_GRIDS_H
#define VP_SAMPLE_VOLUME_GRIDS_H

#include "volphys/volphys.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VOLUME_MAX_GRIDS 2
/* Cells kept on each side of a liquid's surface in a sparse file: OpenVDB's usual narrow band. */
#define VOLUME_LEVEL_SET_HALF_WIDTH 3.0f

/* What a field is, as OpenVDB classes grids. */
typedef enum VolumeGridClass {
  VolumeGridClass_Plain = 0,
  VolumeGridClass_FogVolume = 1, /* a density, 0 where empty */
  VolumeGridClass_LevelSet = 2   /* a signed distance, negative inside: stored within the narrow band only */
} VolumeGridClass;

typedef struct VolumeGrid {
  const char* name;
  VolumeGridClass gridClass;
  float background; /* the value a sparse file gives cells it does not store: 0 for density, the
                       ambient temperature, half-width * cellSize for a level set (outside) */
  float* values;
  int64_t capacity;
} VolumeGrid;

typedef struct VolumeGrids {
  int32_t nx, ny, nz;
  float origin[3]; /* the domain's low corner */
  float cellSize;
  VolumeGrid grids[VOLUME_MAX_GRIDS];
  int gridCount;
} VolumeGrids;

/* Reads the fluid's fields (buffers grown as needed, kept between calls). Returns 0 with a
 * message on stderr on failure. */
int volumeGridsRead(VolumeGrids* volume, vpFluidId fluid);
/* 1 if a sparse file stores this cell: a level set's cells within the narrow band, any other
 * field's cells that differ from its background. */
int volumeGridStores(const VolumeGrid* grid, float value);
void volumeGridsFree(VolumeGrids* volume);

#ifdef __cplusplus
}
#endif

#endif
