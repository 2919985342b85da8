#include "fluid_view.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int report(const char* what, vpStatus s) {
  fprintf(stderr, "fluid view: %s failed (%s): %s\n", what, vpStatusName(s), vpGetLastError());
  return 0;
}

int fluidViewReadSurface(ViewMesh* m, vpFluidId fluid) {
  int32_t nv = 0, nt = 0;
  vpStatus s;
  if ((s = vpFluidGetSurfaceMeshSize(fluid, &nv, &nt)) != vpStatus_Ok) return report("vpFluidGetSurfaceMeshSize", s);
  if (!viewMeshReserve(m, nv, nt)) return 0;
  if ((s = vpFluidGetSurfaceMesh(fluid, m->positions, m->normals, nv, m->triangles, nt)) != vpStatus_Ok)
    return report("vpFluidGetSurfaceMesh", s);
  m->vertexCount = nv;
  m->triangleCount = nt;
  return 1;
}

/* Cells visited when every stride-th cell along each axis is taken. */
static int64_t sampledCells(int32_t nx, int32_t ny, int32_t nz, int32_t stride) {
  return (int64_t)((nx + stride - 1) / stride) * ((ny + stride - 1) / stride) * ((nz + stride - 1) / stride);
}

/* The smallest stride that keeps the visited cells within the point budget: a cheap, even
 * thinning that keeps the plume's shape. */
static int32_t smokeStride(int32_t nx, int32_t ny, int32_t nz) {
  int32_t stride = 1;
  while (sampledCells(nx, ny, nz, stride) > FLUID_VIEW_MAX_SMOKE_POINTS) ++stride;
  return stride;
}

int fluidViewReadSmoke(ViewPoints* p, vpFluidId fluid, float** scratch, int64_t* scratchCount) {
  int32_t nx = 0, ny = 0, nz = 0, i, j, k, stride;
  int64_t cells;
  vpVec3 origin;
  float h = 0.0f, densest = 0.0f;
  const float* rho;
  vpStatus s;
  if ((s = vpFluidGetResolution(fluid, &nx, &ny, &nz)) != vpStatus_Ok) return report("vpFluidGetResolution", s);
  if ((s = vpFluidGetDomain(fluid, &origin, &h)) != vpStatus_Ok) return report("vpFluidGetDomain", s);
  cells = (int64_t)nx * ny * nz;
  if (cells > *scratchCount) {
    float* grown = (float*)realloc(*scratch, sizeof(float) * (size_t)cells);
    if (!grown) return 0;
    *scratch = grown;
    *scratchCount = cells;
  }
  if ((s = vpFluidGetField(fluid, vpFluidField_SmokeDensity, *scratch, cells)) != vpStatus_Ok)
    return report("vpFluidGetField", s);
  rho = *scratch;
  stride = smokeStride(nx, ny, nz);
  for (k = 0; k < nz; k += stride)
    for (j = 0; j < ny; j += stride)
      for (i = 0; i < nx; i += stride) {
        const float d = rho[i + (int64_t)nx * (j + (int64_t)ny * k)];
        if (d > densest) densest = d;
      }
  p->count = 0;
  if (!viewPointsReserve(p, (int32_t)sampledCells(nx, ny, nz, stride))) return 0;
  /* Brightness and opacity relative to this frame's densest cell, so a faint plume is still
   * visible and a dense one does not turn into a solid block. */
  for (k = 0; k < nz; k += stride)
    for (j = 0; j < ny; j += stride)
      for (i = 0; i < nx; i += stride) {
        const float d = rho[i + (int64_t)nx * (j + (int64_t)ny * k)];
        float t, *xyz, *rgba;
        if (d <= FLUID_VIEW_SMOKE_THRESHOLD) continue;
        t = densest > 0.0f ? sqrtf(d / densest) : 0.0f;
        xyz = &p->xyz[3 * p->count];
        rgba = &p->rgba[4 * p->count];
        xyz[0] = origin.x + h * ((float)i + 0.5f);
        xyz[1] = origin.y + h * ((float)j + 0.5f);
        xyz[2] = origin.z + h * ((float)k + 0.5f);
        rgba[0] = 0.45f + 0.5f * t;
        rgba[1] = 0.47f + 0.5f * t;
        rgba[2] = 0.52f + 0.45f * t;
        rgba[3] = 0.1f + 0.6f * t;
        ++p->count;
      }
  return 1;
}
