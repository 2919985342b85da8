#define _POSIX_C_SOURCE 200809L
#include "host_outputs.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "hud_stats.h"
#include "mesh_export.h"

int makeDirectories(const char* path) {
  char buffer[4096];
  size_t n = strlen(path), i;
  if (n == 0 || n >= sizeof buffer) return 0;
  memcpy(buffer, path, n + 1);
  for (i = 1; i <= n; ++i) {
    if (buffer[i] == '/' || buffer[i] == '\0') {
      char saved = buffer[i];
      buffer[i] = '\0';
      if (mkdir(buffer, 0755) != 0 && errno != EEXIST) return 0;
      buffer[i] = saved;
    }
  }
  return 1;
}

static int makeSubfolder(const char* outDir, const char* name) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", outDir, name);
  if (makeDirectories(path)) return 1;
  fprintf(stderr, "volphys_host: cannot create '%s': %s\n", path, strerror(errno));
  return 0;
}

int hostOutputsInit(HostOutputs* o, vpWorldId world, const HostOutputsConfig* config) {
  float centre[3], radius;
  memset(o, 0, sizeof *o);
  o->config = *config;
  o->world = world;
  if (config->exportEvery <= 0 && config->snapshotEvery <= 0) return 1;
  if (config->exportEvery > 0 && !meshExportFormatKnown(config->exportFormat)) {
    fprintf(stderr, "volphys_host: --export-format = '%s': assimp has no such export format (try ply, obj, stl)\n",
            config->exportFormat);
    return 0;
  }
  if (!sceneViewInit(&o->view, world)) return 0;
  sceneViewBounds(&o->view, centre, &radius);
  o->camera = orbitCameraFraming(centre, radius);
  if (config->exportEvery > 0 && !makeSubfolder(config->outDir, "meshes")) return 0;
  if (config->snapshotEvery > 0) {
    if (!makeSubfolder(config->outDir, "snapshots")) return 0;
    if (!(o->snapshot = offscreenSnapshotCreate(config->imageWidth, config->imageHeight))) return 0;
  }
  return 1;
}

static int due(int every, int frame, int frameCount) {
  return every > 0 && (frame % every == 0 || frame == frameCount - 1);
}

static int exportMeshes(HostOutputs* o, int frame) {
  const char* ext = strncmp(o->config.exportFormat, "ply", 3) == 0 ? "ply" : o->config.exportFormat;
  int i;
  for (i = 0; i < o->view.meshCount; ++i) {
    char path[4096];
    const ViewMesh* m = &o->view.meshes[i];
    /* A liquid drained to nothing has no surface; an empty file would only confuse readers. */
    if (!m->exported || m->triangleCount == 0) continue;
    snprintf(path, sizeof path, "%s/meshes/%s_f%05d.%s", o->config.outDir, m->name, frame, ext);
    if (!meshExportWrite(m, o->config.exportFormat, path)) return 0;
    ++o->meshFiles;
  }
  return 1;
}

static int writeSnapshot(HostOutputs* o, int frame) {
  char lines[HUD_MAX_LINES][HUD_LINE_CHARS];
  const char* linePointers[HUD_MAX_LINES];
  char path[4096];
  int n = hudStatsLines(o->world, lines), i;
  for (i = 0; i < n; ++i) linePointers[i] = lines[i];
  snprintf(path, sizeof path, "%s/snapshots/frame_%05d.png", o->config.outDir, frame);
  if (!offscreenSnapshotWrite(o->snapshot, &o->view, &o->camera, linePointers, n, path)) return 0;
  ++o->snapshotFiles;
  return 1;
}

int hostOutputsFrame(HostOutputs* o, int frame, int frameCount) {
  const int exportNow = due(o->config.exportEvery, frame, frameCount);
  const int snapshotNow = due(o->config.snapshotEvery, frame, frameCount);
  if (!exportNow && !snapshotNow) return 1;
  if (!sceneViewUpdate(&o->view)) return 0;
  if (exportNow && !exportMeshes(o, frame)) return 0;
  if (snapshotNow && !writeSnapshot(o, frame)) return 0;
  return 1;
}

void hostOutputsFree(HostOutputs* o) {
  offscreenSnapshotDestroy(o->snapshot);
  sceneViewFree(&o->view);
  memset(o, 0, sizeof *o);
}
