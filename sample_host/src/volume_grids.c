#include "volume_grids.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int report(const char* what, vpStatus s) {
  fprintf(stderr, "volume export: %s failed (%s): %s\n", what, vpStatusName(s), vpGetLastError());
  return 0;
}

static int readGrid(VolumeGrid* g, vpFluidId fluid, vpFluidField field, int64_t cells) {
  vpStatus s;
  if (cells > g->capacity) {
    float* grown = (float*)realloc(g->values, sizeof(float) * (size_t)cells);
    if (!grown) {
      fprintf(stderr, "volume export: out of memory for %lld cells\n", (long long)cells);
      return 0;
    }
    g->values = grown;
    g->capacity = cells;
  }
  if ((s = vpFluidGetField(fluid, field, g->values, cells)) != vpStatus_Ok) return report("vpFluidGetField", s);
  return 1;
}

int volumeGridsRead(VolumeGrids* v, vpFluidId fluid) {
  vpFluidKind kind = vpFluidKind_Smoke;
  vpVec3 origin;
  vpStatus s;
  int64_t cells;
  if ((s = vpFluidGetResolution(fluid, &v->nx, &v->ny, &v->nz)) != vpStatus_Ok)
    return report("vpFluidGetResolution", s);
  if ((s = vpFluidGetDomain(fluid, &origin, &v->cellSize)) != vpStatus_Ok) return report("vpFluidGetDomain", s);
  if ((s = vpFluidGetKind(fluid, &kind)) != vpStatus_Ok) return report("vpFluidGetKind", s);
  v->origin[0] = origin.x;
  v->origin[1] = origin.y;
  v->origin[2] = origin.z;
  cells = (int64_t)v->nx * v->ny * v->nz;
  if (kind == vpFluidKind_Liquid) {
    VolumeGrid* g = &v->grids[0];
    g->name = "level_set";
    g->gridClass = VolumeGridClass_LevelSet;
    g->background = VOLUME_LEVEL_SET_HALF_WIDTH * v->cellSize;
    v->gridCount = 1;
    return readGrid(g, fluid, vpFluidField_LevelSet, cells);
  } else {
    vpFluidParameters p;
    memset(&p, 0, sizeof p);
    p.structSize = sizeof p;
    if ((s = vpFluidGetParameters(fluid, &p)) != vpStatus_Ok) return report("vpFluidGetParameters", s);
    v->grids[0].name = "density";
    v->grids[0].gridClass = VolumeGridClass_FogVolume;
    v->grids[0].background = 0.0f;
    v->grids[1].name = "temperature";
    v->grids[1].gridClass = VolumeGridClass_Plain;
    v->grids[1].background = p.ambientTemperature;
    v->gridCount = 2;
    return readGrid(&v->grids[0], fluid, vpFluidField_SmokeDensity, cells) &&
           readGrid(&v->grids[1], fluid, vpFluidField_Temperature, cells);
  }
}

int volumeGridStores(const VolumeGrid* g, float value) {
  return g->gridClass == VolumeGridClass_LevelSet ? fabsf(value) < g->background : value != g->background;
}

void volumeGridsFree(VolumeGrids* v) {
  int i;
  for (i = 0; i < VOLUME_MAX_GRIDS; ++i) free(v->grids[i].values);
  memset(v, 0, sizeof *v);
}
