/* One step's actors summed by kind, for the per-frame stats CSV and console line: the CSV has
 * fixed columns, so any number of deformables or fluids folds into one set of totals. */
#ifndef VP_SAMPLE_STEP_SUMMARY_H
#define VP_SAMPLE_STEP_SUMMARY_H

#include "volphys/volphys.h"

typedef struct DeformSummary {
  double ms, solveMs, maxResidual;
  int iterations, diverged;
} DeformSummary;

/* Fluid phases: advect, forces (sources, buoyancy, vorticity), fractions (cut cells from the
 * colliders), pressure (the iterative projection), surface (level set upkeep). */
typedef struct FluidSummary {
  double ms, advectMs, forcesMs, fractionsMs, pressureMs, surfaceMs, maxResidual;
  int pressureIterations, diverged, budgetCut;
} FluidSummary;

/* Sums actors 1..actorCount-1 of the last step (entry 0 is the rigid pseudo-actor). */
void summarizeDeformables(vpWorldId world, int actorCount, DeformSummary* out);
void summarizeFluids(vpWorldId world, int actorCount, FluidSummary* out);

#endif
