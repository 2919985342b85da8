/* What the end-of-run summary adds to the frame times: how many frames ran past the budget by
 * more than a tolerated overshoot, each actor's range of step intervals, and the spread of the
 * deformables' final residuals. Actors are named by their labels (actor_labels.h), like the
 * stats columns and the mesh files. */
#ifndef VP_SAMPLE_RUN_SUMMARY_H
#define VP_SAMPLE_RUN_SUMMARY_H

#include <stdio.h>

#include "actor_labels.h"
#include "frame_stats.h"
#include "volphys/volphys.h"

/* A frame counts as over budget past this multiple of it: the clock and the last slice of a
 * frame may overshoot a little, which a host does not notice. */
#define RUN_SUMMARY_OVER_BUDGET_FACTOR 1.1

typedef struct ActorIntervals {
  vpActorKind kind;
  uint32_t index1;
  int minInterval, maxInterval;
} ActorIntervals;

typedef struct RunSummary {
  int frames, overBudgetFrames;
  int frameCapacity;
  ActorIntervals* actors; /* the actors after the rigid pseudo-actor, as the first frame lists them */
  int actorCount;
  FrameTimes deformableResiduals; /* vpActorStats.residual of every deformable in every frame */
} RunSummary;

void runSummaryInit(RunSummary* r, int frameCapacity);
/* After each step; 0 when out of memory. */
int runSummaryAdd(RunSummary* r, vpWorldId world, const vpStepStats* step);
/* Appends ", over 1.1x budget N (P%), intervals jelly 1-2 ..., deformable residual p50 .. p95 .."
 * to the summary line being written to `out`. */
void runSummaryPrint(const RunSummary* r, const ActorLabels* labels, FILE* out);
void runSummaryFree(RunSummary* r);

#endif
