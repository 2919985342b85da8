/* poses.csv: the colliders' poses in the frames the host exports, one row per frame (frame,
 * simulated time, then LABEL_px, _py, _pz, _qx, _qy, _qz, _qw per collider): with the collider
 * meshes written once in their local frames, what a 3D package needs to key their motion. */
#ifndef VP_SAMPLE_COLLIDER_POSES_H
#define VP_SAMPLE_COLLIDER_POSES_H

#include <stdio.h>

#include "actor_labels.h"

/* Creates the file and writes its header; NULL (with a message) on failure. */
FILE* colliderPosesOpen(const char* path, const ActorLabels* labels);
/* One row: after step `frame` (0-based), at simulated time `time`. 0 on failure. */
int colliderPosesWrite(FILE* csv, const ActorLabels* labels, int frame, double time);

#endif
