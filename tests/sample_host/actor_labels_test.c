/* The sample programs' actor labels (actor_labels.h), through the C ABI only: scene names made
 * path- and CSV-safe, numbered names for unnamed actors, unique over all kinds, and never a
 * column of another label or of the CSV files' fixed columns. Exit code: the failed checks. */
#include <stdio.h>
#include <string.h>

#include "actor_labels.h"

static int failures = 0;

static void expectLabel(const char* got, const char* want, const char* what) {
  if (strcmp(got, want) == 0) return;
  printf("FAIL: %s: label '%s', expected '%s'\n", what, got, want);
  ++failures;
}

int main(void) {
  static const char* const colliders[8] = {"rock_pile", "rock_pile-2", "a_b_c_", "collider3",
                                           "time-2",    "_lead",       "collider6", "rock-pile-x"};
  static const char* const deformables[2] = {"fluid-2", "rock_pile-3"};
  static const char* const fluids[4] = {"tank", "tank-2", "fluid2", "deform-2"};
  vpWorldDef def = vpDefaultWorldDef();
  vpWorldId world;
  ActorLabels labels;
  int i;
  if (vpWorldCreate(&def, &world) != vpStatus_Ok) return 1;
  if (vpWorldLoadScene(world, VP_TEST_DATA_DIR "/scenes/awkward_names.json") != vpStatus_Ok) {
    printf("FAIL: loading the scene: %s\n", vpGetLastError());
    return 1;
  }
  if (!actorLabelsInit(&labels, world)) return 1;
  if (labels.colliderCount != 8 || labels.deformableCount != 2 || labels.fluidCount != 5) {
    printf("FAIL: %d colliders, %d deformables, %d fluids listed\n", labels.colliderCount, labels.deformableCount,
           labels.fluidCount);
    return 1;
  }
  /* Spaces and punctuation become '_'; a repeat gets -2; unnamed and unreadable names are
   * numbered; "time" would give time_s, poses.csv's column; a leading '-' becomes '_';
   * rock_pile_x's columns would be rock_pile's. */
  for (i = 0; i < 8; ++i) expectLabel(labels.colliderLabels[i], colliders[i], "collider");
  /* "fluid" and "deform" would give stats.csv's total columns (fluid_ms, deform_ms); labels are
   * unique across kinds (rock_pile, rock_pile-2 are colliders'); tank_2 would extend tank. */
  for (i = 0; i < 2; ++i) expectLabel(labels.deformableLabels[i], deformables[i], "deformable");
  for (i = 0; i < 4; ++i) expectLabel(labels.fluidLabels[i], fluids[i], "fluid");
  /* A long name is cut, leaving room for a suffix. */
  if (strlen(labels.fluidLabels[4]) + 12 != ACTOR_LABEL_CHARS - 1 || labels.fluidLabels[4][0] != 'x') {
    printf("FAIL: long name labelled '%s'\n", labels.fluidLabels[4]);
    ++failures;
  }
  actorLabelsFree(&labels);
  vpWorldDestroy(world);
  printf("%s\n", failures ? "actor labels: FAILED" : "actor labels OK");
  return failures;
}
