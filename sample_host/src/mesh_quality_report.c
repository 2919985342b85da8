#include "mesh_quality_report.h"

int printMeshQuality(FILE* out, const ActorLabels* labels) {
  int i;
  for (i = 0; i < labels->deformableCount; ++i) {
    float minAngle = 0.0f, maxAngle = 0.0f, tetVolume = 0.0f, surfaceVolume = 0.0f;
    vpStatus s = vpDeformableGetMeshQuality(labels->deformables[i], &minAngle, &maxAngle, &tetVolume, &surfaceVolume);
    if (s != vpStatus_Ok) {
      fprintf(stderr, "vpDeformableGetMeshQuality: %s (%s)\n", vpGetLastError(), vpStatusName(s));
      return 0;
    }
    fprintf(out, "mesh %s: dihedral angles %.1f-%.1f deg, volume %.4g m^3 (surface %.4g m^3, ratio %.2f)\n",
            labels->deformableLabels[i], minAngle, maxAngle, tetVolume, surfaceVolume,
            surfaceVolume > 0.0f ? tetVolume / surfaceVolume : 0.0f);
  }
  return 1;
}
