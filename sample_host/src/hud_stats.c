#include "hud_stats.h"

#include <stdio.h>
#include <string.h>

#include "phase_names.h"

static const char* const kKindNames[3] = {"rigid", "deformable", "fluid"};

int hudStatsLines(vpWorldId world, const ActorLabels* labels, char lines[HUD_MAX_LINES][HUD_LINE_CHARS]) {
  vpStepStats step = vpDefaultStepStats();
  int n = 0, a;
  if (vpWorldGetStepStats(world, &step) != vpStatus_Ok) return 0;
  snprintf(lines[n++], HUD_LINE_CHARS, "frame %llu  step %.2f ms / budget %.1f ms%s%s", (unsigned long long)step.stepIndex,
           step.totalMs, step.budgetMs, step.budgetMs <= 0.0f ? " (unlimited)" : step.budgetCut ? "  CUT" : "",
           step.budgetInfeasible ? "  INFEASIBLE" : step.fluidInterval > 1 ? "  fluid steps span frames" : "");
  for (a = 0; a < step.actorCount && n < HUD_MAX_LINES; ++a) {
    vpActorStats s = vpDefaultActorStats();
    size_t used;
    int p;
    const char* label;
    char* line = lines[n++];
    if (vpWorldGetActorStats(world, a, &s) != vpStatus_Ok) break;
    /* The rigid pseudo-actor has no id; an actor the labels do not know is shown by its slot. */
    label = actorLabelOfStats(labels, &s);
    if (s.kind == vpActorKind_Rigid)
      used = (size_t)snprintf(line, HUD_LINE_CHARS, "bullet %.2f ms:", s.totalMs);
    else if (label)
      used = (size_t)snprintf(line, HUD_LINE_CHARS, "%s %s %.2f ms:",
                              kKindNames[(int)s.kind >= 0 && s.kind < 3 ? s.kind : 0], label, s.totalMs);
    else
      used = (size_t)snprintf(line, HUD_LINE_CHARS, "%s #%u %.2f ms:",
                              kKindNames[(int)s.kind >= 0 && s.kind < 3 ? s.kind : 0], s.index1, s.totalMs);
    for (p = 0; p < vpPhase_Count && used < HUD_LINE_CHARS; ++p) {
      const vpPhaseStats* ph = &s.phases[p];
      if (ph->ms <= 0.0f && ph->iterations == 0) continue;
      used += (size_t)snprintf(line + used, HUD_LINE_CHARS - used, " %s %.2f", phaseName(p), ph->ms);
      if (ph->iterations > 0 && used < HUD_LINE_CHARS)
        used += (size_t)snprintf(line + used, HUD_LINE_CHARS - used, " (%d its, res %.0e%s)", ph->iterations,
                                 ph->residual, ph->budgetCut ? ", cut" : "");
    }
    /* A fluid step may span frames; readers see the last completed one meanwhile. */
    if (s.kind == vpActorKind_Fluid && s.progress < 1.0f && used < HUD_LINE_CHARS)
      used += (size_t)snprintf(line + used, HUD_LINE_CHARS - used, " step %.0f%%", 100.0 * s.progress);
    if (s.interval > 1 && used < HUD_LINE_CHARS)
      used += (size_t)snprintf(line + used, HUD_LINE_CHARS - used, " every %d frames", s.interval);
    if (s.diverged && used < HUD_LINE_CHARS) snprintf(line + used, HUD_LINE_CHARS - used, " DIVERGED");
  }
  return n;
}
