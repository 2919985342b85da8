#include "run_summary.h"

#include <stdlib.h>
#include <string.h>

void runSummaryInit(RunSummary* r, int frameCapacity) {
  memset(r, 0, sizeof *r);
  r->frameCapacity = frameCapacity;
}

/* The first frame lists the actors; the residual buffer holds every deformable's frames. */
static int startActors(RunSummary* r, vpWorldId world, int actorCount) {
  int a, deformables = 0;
  r->actorCount = actorCount > 1 ? actorCount - 1 : 0;
  r->actors = (ActorIntervals*)calloc((size_t)(r->actorCount > 0 ? r->actorCount : 1), sizeof *r->actors);
  if (!r->actors) return 0;
  for (a = 0; a < r->actorCount; ++a) {
    vpActorStats s = vpDefaultActorStats();
    if (vpWorldGetActorStats(world, a + 1, &s) != vpStatus_Ok) s.kind = vpActorKind_Rigid;
    r->actors[a].kind = s.kind;
    r->actors[a].index1 = s.index1;
    r->actors[a].minInterval = r->actors[a].maxInterval = -1;
    deformables += s.kind == vpActorKind_Deformable;
  }
  return frameTimesInit(&r->deformableResiduals, r->frameCapacity * deformables);
}

int runSummaryAdd(RunSummary* r, vpWorldId world, const vpStepStats* step) {
  int a;
  if (r->frames == 0 && !startActors(r, world, step->actorCount)) return 0;
  ++r->frames;
  if (step->budgetMs > 0.0f && step->totalMs > RUN_SUMMARY_OVER_BUDGET_FACTOR * step->budgetMs) ++r->overBudgetFrames;
  for (a = 0; a < r->actorCount && a + 1 < step->actorCount; ++a) {
    ActorIntervals* i = &r->actors[a];
    vpActorStats s = vpDefaultActorStats();
    if (vpWorldGetActorStats(world, a + 1, &s) != vpStatus_Ok || s.kind != i->kind) continue;
    if (i->minInterval < 0 || s.interval < i->minInterval) i->minInterval = s.interval;
    if (s.interval > i->maxInterval) i->maxInterval = s.interval;
    if (s.kind == vpActorKind_Deformable) frameTimesAdd(&r->deformableResiduals, s.residual);
  }
  return 1;
}

void runSummaryPrint(const RunSummary* r, const ActorLabels* labels, FILE* out) {
  int a;
  fprintf(out, ", over %.1fx budget %d (%.1f%%)", RUN_SUMMARY_OVER_BUDGET_FACTOR, r->overBudgetFrames,
          r->frames ? 100.0 * r->overBudgetFrames / r->frames : 0.0);
  if (r->actorCount > 0) fprintf(out, ", intervals");
  for (a = 0; a < r->actorCount; ++a) {
    const ActorIntervals* i = &r->actors[a];
    vpActorStats s = vpDefaultActorStats();
    const char* label;
    s.kind = i->kind;
    s.index1 = i->index1;
    if (!(label = actorLabelOfStats(labels, &s))) continue;
    fprintf(out, " %s %d-%d", label, i->minInterval, i->maxInterval);
  }
  if (r->deformableResiduals.count > 0)
    fprintf(out, ", deformable residual p50 %.1e p95 %.1e", frameTimesPercentile(&r->deformableResiduals, 0.5),
            frameTimesPercentile(&r->deformableResiduals, 0.95));
}

void runSummaryFree(RunSummary* r) {
  free(r->actors);
  frameTimesFree(&r->deformableResiduals);
  memset(r, 0, sizeof *r);
}
