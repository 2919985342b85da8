/* The sample host's per-frame files besides stats.csv: every `exportEvery` frames and on the
 * last, meshes of the deformables and liquid surfaces (assimp), the colliders' poses
 * (poses.csv; the last frame's even with exports off) and the fluids' volumes (OpenVDB or VTK
 * image data); the collider meshes once, in their local frames; PNG snapshots (offscreen)
 * every `snapshotEvery` frames and on the last. 0 turns either period off. */
#ifndef VP_SAMPLE_HOST_OUTPUTS_H
#define VP_SAMPLE_HOST_OUTPUTS_H

#include <stdio.h>

#include "actor_labels.h"
#include "offscreen_snapshot.h"
#include "orbit_camera.h"
#include "scene_view.h"
#include "volume_grids.h"

typedef enum VolumeFormat { VolumeFormat_None = 0, VolumeFormat_Vdb = 1, VolumeFormat_Vti = 2 } VolumeFormat;

typedef struct HostOutputsConfig {
  const char* outDir;
  double dt;                /* seconds per frame: poses.csv's time column */
  int exportEvery;
  const char* exportFormat; /* assimp id; also the file extension ("plyb" writes .ply) */
  VolumeFormat volumeFormat;
  int snapshotEvery;
  int imageWidth, imageHeight;
} HostOutputsConfig;

typedef struct HostOutputs {
  HostOutputsConfig config;
  vpWorldId world;
  const ActorLabels* labels;
  SceneView view;
  OrbitCamera camera;
  OffscreenSnapshot* snapshot;
  FILE* poses;
  VolumeGrids volume; /* one fluid's fields at a time */
  int meshFiles, volumeFiles, snapshotFiles;
} HostOutputs;

/* Creates DIR/meshes, DIR/volumes and DIR/snapshots as needed, poses.csv and the collider
 * meshes. `labels` must outlive the outputs. Returns 0 with a message on failure. */
int hostOutputsInit(HostOutputs* o, vpWorldId world, const ActorLabels* labels, const HostOutputsConfig* config);
/* After step `frame` (0-based) of `frameCount`. */
int hostOutputsFrame(HostOutputs* o, int frame, int frameCount);
void hostOutputsFree(HostOutputs* o);

/* mkdir -p; 1 on success. */
int makeDirectories(const char* path);

#endif
