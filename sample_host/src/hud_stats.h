/* The on-screen summary of the last step: total against the budget, then each actor's time
 * and the phases it spent it in (solver iterations and residual where it iterated). Shared by
 * the viewer and the snapshots. Actors are shown by kind and label (actor_labels.h), as in the
 * files the host writes. */
#ifndef VP_SAMPLE_HUD_STATS_H
#define VP_SAMPLE_HUD_STATS_H

#include "actor_labels.h"
#include "volphys/volphys.h"

#define HUD_MAX_LINES 16
#define HUD_LINE_CHARS 160

/* Returns the number of lines written (at most HUD_MAX_LINES). */
int hudStatsLines(vpWorldId world, const ActorLabels* labels, char lines[HUD_MAX_LINES][HUD_LINE_CHARS]);

#endif
