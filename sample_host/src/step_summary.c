#include "step_summary.h"

#include <string.h>

void summarizeDeformables(vpWorldId world, int actorCount, DeformSummary* out) {
  int a;
  memset(out, 0, sizeof *out);
  for (a = 1; a < actorCount; ++a) {
    vpActorStats s = vpDefaultActorStats();
    if (vpWorldGetActorStats(world, a, &s) != vpStatus_Ok || s.kind != vpActorKind_Deformable) continue;
    out->ms += s.totalMs;
    out->solveMs += s.phases[vpPhase_Solve].ms;
    out->iterations += s.phases[vpPhase_Solve].iterations;
    if (s.phases[vpPhase_Solve].residual > out->maxResidual) out->maxResidual = s.phases[vpPhase_Solve].residual;
    out->diverged += s.diverged;
  }
}

void summarizeFluids(vpWorldId world, int actorCount, FluidSummary* out) {
  int a;
  memset(out, 0, sizeof *out);
  for (a = 1; a < actorCount; ++a) {
    vpActorStats s = vpDefaultActorStats();
    const vpPhaseStats* pressure;
    if (vpWorldGetActorStats(world, a, &s) != vpStatus_Ok || s.kind != vpActorKind_Fluid) continue;
    pressure = &s.phases[vpPhase_Pressure];
    out->ms += s.totalMs;
    out->advectMs += s.phases[vpPhase_Advect].ms;
    out->forcesMs += s.phases[vpPhase_Forces].ms;
    out->fractionsMs += s.phases[vpPhase_Fractions].ms;
    out->pressureMs += pressure->ms;
    out->surfaceMs += s.phases[vpPhase_Surface].ms;
    out->pressureIterations += pressure->iterations;
    if (pressure->residual > out->maxResidual) out->maxResidual = pressure->residual;
    out->budgetCut += pressure->budgetCut;
    out->diverged += s.diverged;
  }
}
