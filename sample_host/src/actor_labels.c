#include "actor_labels.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv_columns.h"

/* Room left in a label for a -N suffix. */
#define BASE_CHARS (ACTOR_LABEL_CHARS - 12)

enum { kPosesCsv = 0, kStatsCsv = 1 };

static int report(const char* what, vpStatus s) {
  fprintf(stderr, "actor labels: %s failed (%s): %s\n", what, vpStatusName(s), vpGetLastError());
  return 0;
}

/* `text` is `word` followed by '_' and more: LABEL_x columns of the two could coincide. */
static int extendsWord(const char* text, const char* word, size_t wordLength) {
  return strncmp(text, word, wordLength) == 0 && text[wordLength] == '_';
}

static int extendsColumn(const char* label, const char* columns) {
  const size_t n = strlen(label);
  const char* c = columns;
  for (; c; c = strchr(c, ','), c = c ? c + 1 : NULL)
    if (extendsWord(c, label, n)) return 1;
  return 0;
}

typedef struct Assigned {
  const char* label;
  int csv;
} Assigned;

static int clashes(const char* candidate, int csv, const Assigned* assigned, int count) {
  const size_t n = strlen(candidate);
  int i;
  if (extendsColumn(candidate, csv == kPosesCsv ? POSES_CSV_FIXED_COLUMNS : STATS_CSV_TOTAL_COLUMNS)) return 1;
  for (i = 0; i < count; ++i) {
    if (strcmp(candidate, assigned[i].label) == 0) return 1;
    if (assigned[i].csv == csv &&
        (extendsWord(assigned[i].label, candidate, n) || extendsWord(candidate, assigned[i].label, strlen(assigned[i].label))))
      return 1;
  }
  return 0;
}

/* The name made path- and CSV-safe, or `fallback` when that leaves nothing readable. */
static void baseLabel(const char* name, const char* fallback, char out[BASE_CHARS]) {
  size_t i, n = strlen(name);
  int readable = 0;
  if (n > BASE_CHARS - 1) n = BASE_CHARS - 1;
  for (i = 0; i < n; ++i) {
    const char c = name[i];
    const int alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    readable |= alnum;
    /* A leading '-' would read as an option to command-line tools. */
    out[i] = alnum || c == '_' || (c == '-' && i > 0) ? c : '_';
  }
  out[n] = '\0';
  if (!readable) snprintf(out, BASE_CHARS, "%s", fallback);
}

/* `label` is another label of its CSV followed by '_': no suffix would make their columns differ. */
static int extendsLabel(const char* label, int csv, const Assigned* assigned, int count) {
  int i;
  for (i = 0; i < count; ++i)
    if (assigned[i].csv == csv && extendsWord(label, assigned[i].label, strlen(assigned[i].label))) return 1;
  return 0;
}

static void assign(const char* name, const char* fallback, int csv, Assigned* assigned, int* count, char* out) {
  char base[BASE_CHARS], *c;
  int suffix = 1;
  baseLabel(name, fallback, base);
  if (extendsLabel(base, csv, assigned, *count))
    for (c = base; *c; ++c)
      if (*c == '_') *c = '-';
  snprintf(out, ACTOR_LABEL_CHARS, "%s", base);
  while (clashes(out, csv, assigned, *count)) snprintf(out, ACTOR_LABEL_CHARS, "%s-%d", base, ++suffix);
  assigned[*count].label = out;
  assigned[*count].csv = csv;
  ++*count;
}

/* Each kind's name getter, behind one signature. */
typedef vpStatus NameGetter(const void* id, char* buffer, int32_t capacity, int32_t* outLength);
static vpStatus colliderName(const void* id, char* b, int32_t c, int32_t* n) {
  return vpColliderGetName(*(const vpColliderId*)id, b, c, n);
}
static vpStatus deformableName(const void* id, char* b, int32_t c, int32_t* n) {
  return vpDeformableGetName(*(const vpDeformableId*)id, b, c, n);
}
static vpStatus fluidName(const void* id, char* b, int32_t c, int32_t* n) {
  return vpFluidGetName(*(const vpFluidId*)id, b, c, n);
}

/* The actor's scene name (malloc'd; the caller frees it), NULL on failure. */
static char* readName(NameGetter* get, const void* id) {
  int32_t length = 0;
  char* name;
  vpStatus s;
  if ((s = get(id, NULL, 0, &length)) != vpStatus_Ok) return report("reading a name's length", s), NULL;
  if (!(name = (char*)malloc((size_t)length))) return NULL;
  if ((s = get(id, name, length, &length)) != vpStatus_Ok) {
    free(name);
    return report("reading a name", s), NULL;
  }
  return name;
}

static int labelKind(NameGetter* get, const void* ids, size_t idSize, int count, const char* kind, int csv,
                     ActorLabel* labels, Assigned* assigned, int* assignedCount) {
  int i;
  for (i = 0; i < count; ++i) {
    char fallback[BASE_CHARS];
    char* name = readName(get, (const char*)ids + (size_t)i * idSize);
    if (!name) return 0;
    snprintf(fallback, sizeof fallback, "%s%d", kind, i);
    assign(name, fallback, csv, assigned, assignedCount, labels[i]);
    free(name);
  }
  return 1;
}

/* calloc of at least one item, so that an empty list is not mistaken for a failure. */
static void* allocItems(int count, size_t size) { return calloc((size_t)(count > 0 ? count : 1), size); }

static int listIds(ActorLabels* l, vpWorldId world) {
  vpStatus s;
  int32_t n;
  if ((s = vpWorldGetColliderCount(world, &n)) != vpStatus_Ok) return report("vpWorldGetColliderCount", s);
  l->colliders = (vpColliderId*)allocItems(n, sizeof *l->colliders);
  l->colliderLabels = (ActorLabel*)allocItems(n, sizeof *l->colliderLabels);
  if (!l->colliders || !l->colliderLabels) return 0;
  if ((s = vpWorldGetColliders(world, l->colliders, n, &n)) != vpStatus_Ok) return report("vpWorldGetColliders", s);
  l->colliderCount = n;
  if ((s = vpWorldGetDeformableCount(world, &n)) != vpStatus_Ok) return report("vpWorldGetDeformableCount", s);
  l->deformables = (vpDeformableId*)allocItems(n, sizeof *l->deformables);
  l->deformableLabels = (ActorLabel*)allocItems(n, sizeof *l->deformableLabels);
  if (!l->deformables || !l->deformableLabels) return 0;
  if ((s = vpWorldGetDeformables(world, l->deformables, n, &n)) != vpStatus_Ok)
    return report("vpWorldGetDeformables", s);
  l->deformableCount = n;
  if ((s = vpWorldGetFluidCount(world, &n)) != vpStatus_Ok) return report("vpWorldGetFluidCount", s);
  l->fluids = (vpFluidId*)allocItems(n, sizeof *l->fluids);
  l->fluidLabels = (ActorLabel*)allocItems(n, sizeof *l->fluidLabels);
  if (!l->fluids || !l->fluidLabels) return 0;
  if ((s = vpWorldGetFluids(world, l->fluids, n, &n)) != vpStatus_Ok) return report("vpWorldGetFluids", s);
  l->fluidCount = n;
  return 1;
}

int actorLabelsInit(ActorLabels* l, vpWorldId world) {
  Assigned* assigned;
  int count = 0, ok;
  memset(l, 0, sizeof *l);
  if (!listIds(l, world)) {
    actorLabelsFree(l);
    return 0;
  }
  assigned = (Assigned*)allocItems(l->colliderCount + l->deformableCount + l->fluidCount, sizeof *assigned);
  ok = assigned &&
       labelKind(colliderName, l->colliders, sizeof *l->colliders, l->colliderCount, "collider", kPosesCsv,
                 l->colliderLabels, assigned, &count) &&
       labelKind(deformableName, l->deformables, sizeof *l->deformables, l->deformableCount, "deformable",
                 kStatsCsv, l->deformableLabels, assigned, &count) &&
       labelKind(fluidName, l->fluids, sizeof *l->fluids, l->fluidCount, "fluid", kStatsCsv, l->fluidLabels,
                 assigned, &count);
  free(assigned);
  if (!ok) actorLabelsFree(l);
  return ok;
}

const char* actorLabelOfStats(const ActorLabels* l, const vpActorStats* s) {
  int i;
  if (s->kind == vpActorKind_Deformable) {
    for (i = 0; i < l->deformableCount; ++i)
      if (l->deformables[i].index1 == s->index1) return l->deformableLabels[i];
  } else if (s->kind == vpActorKind_Fluid) {
    for (i = 0; i < l->fluidCount; ++i)
      if (l->fluids[i].index1 == s->index1) return l->fluidLabels[i];
  }
  return NULL;
}

void actorLabelsFree(ActorLabels* l) {
  free(l->colliders);
  free(l->colliderLabels);
  free(l->deformables);
  free(l->deformableLabels);
  free(l->fluids);
  free(l->fluidLabels);
  memset(l, 0, sizeof *l);
}
