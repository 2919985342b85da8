/* The sample host's per-frame files besides stats.csv: meshes of the exported actors (assimp)
 * every `exportEvery` frames and PNG snapshots (offscreen) every `snapshotEvery` frames, both
 * also on the last frame; 0 turns either off. */
#ifndef VP_SAMPLE_HOST_OUTPUTS_H
#define VP_SAMPLE_HOST_OUTPUTS_H

#include "offscreen_snapshot.h"
#include "orbit_camera.h"
#include "scene_view.h"

typedef struct HostOutputsConfig {
  const char* outDir;
  int exportEvery;
  const char* exportFormat; /* assimp id; also the file extension ("plyb" writes .ply) */
  int snapshotEvery;
  int imageWidth, imageHeight;
} HostOutputsConfig;

typedef struct HostOutputs {
  HostOutputsConfig config;
  vpWorldId world;
  SceneView view;
  OrbitCamera camera;
  OffscreenSnapshot* snapshot;
  int meshFiles, snapshotFiles;
} HostOutputs;

/* Creates DIR/meshes and DIR/snapshots as needed. Returns 0 with a message on failure. */
int hostOutputsInit(HostOutputs* o, vpWorldId world, const HostOutputsConfig* config);
/* After step `frame` (0-based) of `frameCount`. */
int hostOutputsFrame(HostOutputs* o, int frame, int frameCount);
void hostOutputsFree(HostOutputs* o);

/* mkdir -p; 1 on success. */
int makeDirectories(const char* path);

#endif
