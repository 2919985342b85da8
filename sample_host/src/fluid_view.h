/* A fluid as the two things the sample host draws: a liquid's free surface as a ViewMesh (world
 * space, exported like a deformable) and smoke as ViewPoints at the cells holding smoke. */
#ifndef VP_SAMPLE_FLUID_VIEW_H
#define VP_SAMPLE_FLUID_VIEW_H

#include "scene_view.h"

/* Smoke cells thinner than this are not drawn. */
#define FLUID_VIEW_SMOKE_THRESHOLD 0.02f
/* At most about this many smoke points per fluid: the grid is subsampled with a stride. */
#define FLUID_VIEW_MAX_SMOKE_POINTS 20000

/* Reads the liquid surface into `mesh`. Returns 0 (with a message on stderr) on failure. */
int fluidViewReadSurface(ViewMesh* mesh, vpFluidId fluid);
/* Fills `points` with the cells whose smoke density is above the threshold, coloured and
 * faded by density. `scratch` holds a copy of the density field between calls (grown here;
 * the caller frees it). */
int fluidViewReadSmoke(ViewPoints* points, vpFluidId fluid, float** scratch, int64_t* scratchCount);

#endif
