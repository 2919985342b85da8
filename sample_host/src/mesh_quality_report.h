/* One line per deformable before the run: its tets' dihedral angle range and its volume against
 * its surface's (vpDeformableGetMeshQuality), so a swollen or badly shaped mesh is seen at once. */
#ifndef VP_SAMPLE_MESH_QUALITY_REPORT_H
#define VP_SAMPLE_MESH_QUALITY_REPORT_H

#include <stdio.h>

#include "actor_labels.h"

/* Returns 0 if the ABI refuses (the message is printed to stderr). */
int printMeshQuality(FILE* out, const ActorLabels* labels);

#endif
