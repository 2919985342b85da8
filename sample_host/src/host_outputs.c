#define _POSIX_C_SOURCE 200809L
#include "host_outputs.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "collider_poses.h"
#include "hud_stats.h"
#include "mesh_export.h"
#include "volume_export_vdb.h"
#include "volume_export_vti.h"

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

static const char* meshExtension(const HostOutputsConfig* c) {
  return strncmp(c->exportFormat, "ply", 3) == 0 ? "ply" : c->exportFormat;
}

/* Rigid shapes never change: each collider's mesh once, in its local frame, for poses.csv to
 * place. */
static int exportColliderMeshes(HostOutputs* o) {
  int i;
  for (i = 0; i < o->view.meshCount; ++i) {
    char path[4096];
    ViewMesh local = o->view.meshes[i];
    if (vpColliderIdIsNull(o->view.sources[i].collider)) continue;
    local.pose.position.x = local.pose.position.y = local.pose.position.z = 0.0f;
    local.pose.rotation.x = local.pose.rotation.y = local.pose.rotation.z = 0.0f;
    local.pose.rotation.w = 1.0f;
    snprintf(path, sizeof path, "%s/meshes/%s.%s", o->config.outDir, local.name, meshExtension(&o->config));
    if (!meshExportWrite(&local, o->config.exportFormat, path)) return 0;
    ++o->meshFiles;
  }
  return 1;
}

int hostOutputsInit(HostOutputs* o, vpWorldId world, const ActorLabels* labels, const HostOutputsConfig* config) {
  char path[4096];
  float centre[3], radius;
  const int exporting = config->exportEvery > 0;
  memset(o, 0, sizeof *o);
  o->config = *config;
  o->world = world;
  o->labels = labels;
  if (exporting && !meshExportFormatKnown(config->exportFormat)) {
    fprintf(stderr, "volphys_host: --export-format = '%s': assimp has no such export format (try ply, obj, stl)\n",
            config->exportFormat);
    return 0;
  }
  snprintf(path, sizeof path, "%s/poses.csv", config->outDir);
  if (!(o->poses = colliderPosesOpen(path, labels))) return 0;
  if (!exporting && config->snapshotEvery <= 0) return 1;
  if (!sceneViewInit(&o->view, labels)) return 0;
  sceneViewBounds(&o->view, centre, &radius);
  o->camera = orbitCameraFraming(centre, radius);
  if (exporting && (!makeSubfolder(config->outDir, "meshes") || !exportColliderMeshes(o))) return 0;
  if (exporting && config->volumeFormat != VolumeFormat_None && !makeSubfolder(config->outDir, "volumes")) return 0;
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
  int i;
  for (i = 0; i < o->view.meshCount; ++i) {
    char path[4096];
    const ViewMesh* m = &o->view.meshes[i];
    /* A liquid drained to nothing has no surface; an empty file would only confuse readers. */
    if (!m->exported || m->triangleCount == 0) continue;
    snprintf(path, sizeof path, "%s/meshes/%s_f%05d.%s", o->config.outDir, m->name, frame, meshExtension(&o->config));
    if (!meshExportWrite(m, o->config.exportFormat, path)) return 0;
    ++o->meshFiles;
  }
  return 1;
}

static int exportVolumes(HostOutputs* o, int frame) {
  const int vdb = o->config.volumeFormat == VolumeFormat_Vdb;
  int i;
  for (i = 0; i < o->labels->fluidCount; ++i) {
    char path[4096];
    snprintf(path, sizeof path, "%s/volumes/%s_f%05d.%s", o->config.outDir, o->labels->fluidLabels[i], frame,
             vdb ? "vdb" : "vti");
    if (!volumeGridsRead(&o->volume, o->labels->fluids[i])) return 0;
    if (!(vdb ? volumeExportVdb(&o->volume, path) : volumeExportVti(&o->volume, path))) return 0;
    ++o->volumeFiles;
  }
  return 1;
}

static int writeSnapshot(HostOutputs* o, int frame) {
  char lines[HUD_MAX_LINES][HUD_LINE_CHARS];
  const char* linePointers[HUD_MAX_LINES];
  char path[4096];
  int n = hudStatsLines(o->world, o->labels, lines), i;
  for (i = 0; i < n; ++i) linePointers[i] = lines[i];
  snprintf(path, sizeof path, "%s/snapshots/frame_%05d.png", o->config.outDir, frame);
  if (!offscreenSnapshotWrite(o->snapshot, &o->view, &o->camera, linePointers, n, path)) return 0;
  ++o->snapshotFiles;
  return 1;
}

int hostOutputsFrame(HostOutputs* o, int frame, int frameCount) {
  const int exportNow = due(o->config.exportEvery, frame, frameCount);
  const int snapshotNow = due(o->config.snapshotEvery, frame, frameCount);
  const int last = frame == frameCount - 1;
  if ((exportNow || last) && !colliderPosesWrite(o->poses, o->labels, frame, (frame + 1) * o->config.dt)) return 0;
  if (last && fflush(o->poses) != 0) {
    fprintf(stderr, "volphys_host: writing poses.csv failed: %s\n", strerror(errno));
    return 0;
  }
  if (exportNow && o->config.volumeFormat != VolumeFormat_None && !exportVolumes(o, frame)) return 0;
  if (!exportNow && !snapshotNow) return 1;
  if (!sceneViewUpdate(&o->view)) return 0;
  if (exportNow && !exportMeshes(o, frame)) return 0;
  if (snapshotNow && !writeSnapshot(o, frame)) return 0;
  return 1;
}

void hostOutputsFree(HostOutputs* o) {
  if (o->poses) fclose(o->poses);
  volumeGridsFree(&o->volume);
  offscreenSnapshotDestroy(o->snapshot);
  sceneViewFree(&o->view);
  memset(o, 0, sizeof *o);
}
