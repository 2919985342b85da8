#include "collider_poses.h"

#include <errno.h>
#include <string.h>

#include "csv_columns.h"

FILE* colliderPosesOpen(const char* path, const ActorLabels* labels) {
  static const char* const kAxes[7] = {"px", "py", "pz", "qx", "qy", "qz", "qw"};
  int i, a;
  FILE* f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "volphys_host: cannot write '%s': %s\n", path, strerror(errno));
    return NULL;
  }
  fprintf(f, "%s", POSES_CSV_FIXED_COLUMNS);
  for (i = 0; i < labels->colliderCount; ++i)
    for (a = 0; a < 7; ++a) fprintf(f, ",%s_%s", labels->colliderLabels[i], kAxes[a]);
  fputc('\n', f);
  return f;
}

int colliderPosesWrite(FILE* f, const ActorLabels* labels, int frame, double time) {
  int i;
  vpStatus s;
  fprintf(f, "%d,%.6f", frame, time);
  for (i = 0; i < labels->colliderCount; ++i) {
    vpTransform t;
    if ((s = vpColliderGetPose(labels->colliders[i], &t)) != vpStatus_Ok) {
      fprintf(stderr, "volphys_host: vpColliderGetPose failed (%s): %s\n", vpStatusName(s), vpGetLastError());
      return 0;
    }
    fprintf(f, ",%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f", t.position.x, t.position.y, t.position.z, t.rotation.x,
            t.rotation.y, t.rotation.z, t.rotation.w);
  }
  fputc('\n', f);
  return !ferror(f);
}
