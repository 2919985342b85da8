/* What the sample programs call a world's colliders, deformables and fluids in file names, CSV
 * columns and the HUD: the scene's name with every character other than a letter, digit, '_'
 * or '-' replaced by '_' (so it is safe in a path and a CSV header), or colliderK /
 * deformableK / fluidK (K: its place in the world's list of its kind) when it has none.
 * Labels are unique over all three kinds (their files share a folder); a repeated one gets -2,
 * -3, ... So that no two CSV columns are the same, no label is another label of its CSV
 * (colliders: poses.csv; deformables and fluids: stats.csv) followed by '_', nor the start of
 * one of that file's fixed columns (csv_columns.h) followed by '_': a fluid named "fluid"
 * becomes "fluid-2", and a fluid "tank_2" next to a fluid "tank" becomes "tank-2" (its '_'
 * turned into '-'). */
#ifndef VP_SAMPLE_ACTOR_LABELS_H
#define VP_SAMPLE_ACTOR_LABELS_H

#include "volphys/volphys.h"

#define ACTOR_LABEL_CHARS 64

typedef char ActorLabel[ACTOR_LABEL_CHARS];

typedef struct ActorLabels {
  vpColliderId* colliders;
  ActorLabel* colliderLabels;
  int colliderCount;
  vpDeformableId* deformables;
  ActorLabel* deformableLabels;
  int deformableCount;
  vpFluidId* fluids;
  ActorLabel* fluidLabels;
  int fluidCount;
} ActorLabels;

/* Lists the world's colliders, deformables and fluids (slot order) and labels them. Returns 0
 * with a message on stderr if the ABI refuses or memory runs out. */
int actorLabelsInit(ActorLabels* labels, vpWorldId world);
/* The label of the deformable or fluid an entry of vpWorldGetActorStats describes; NULL for the
 * rigid pseudo-actor and actors created after actorLabelsInit. */
const char* actorLabelOfStats(const ActorLabels* labels, const vpActorStats* stats);
void actorLabelsFree(ActorLabels* labels);

#endif
