/* Compiled as strict C99 (-pedantic-errors -Werror): proves the public header is C-clean,
 * and exercises the basic lifecycle through the C ABI only. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "volphys/volphys.h"

int main(void) {
  vpWorldDef def = vpDefaultWorldDef();
  vpColliderDef ground = vpDefaultColliderDef();
  vpColliderDef ball = vpDefaultColliderDef();
  vpWorldId world;
  vpColliderId groundId, ballId;
  vpTransform pose;
  vpStepStats stats = vpDefaultStepStats();
  int i;
  size_t stateSize = 0;
  unsigned char* state;
  const int32_t boxCells[3] = {2, 1, 1};
  vpVec3 boxSize = {0.4f, 0.2f, 0.2f}, boxCorner = {-0.2f, 1.0f, -0.1f};
  float boxVertices[3 * 12];
  int32_t boxTets[4 * 12];
  int32_t boxVertexCount = 0, boxTetCount = 0;
  vpDeformableDef block = vpDefaultDeformableDef();
  vpDeformableId blockId;
  char name[8];
  int32_t nameLength = 0;

  if (vpCheckVersion() != vpStatus_Ok) return 1;
  if (vpWorldCreate(&def, &world) != vpStatus_Ok) return 2;

  ground.shape.type = vpShapeType_Plane;
  if (vpColliderCreate(world, &ground, &groundId) != vpStatus_Ok) return 3;
  ball.bodyType = vpBodyType_Dynamic;
  ball.shape.radius = 0.5f;
  ball.pose.position.y = 2.0f;
  if (vpColliderCreate(world, &ball, &ballId) != vpStatus_Ok) return 4;

  for (i = 0; i < 120; ++i)
    if (vpWorldStep(world, 1.0f / 60.0f) != vpStatus_Ok) return 5;
  if (vpColliderGetPose(ballId, &pose) != vpStatus_Ok) return 6;
  if (vpWorldGetStepStats(world, &stats) != vpStatus_Ok || stats.stepIndex != 120) return 7;
  /* After two seconds the ball rests on the plane: centre at its radius. */
  if (pose.position.y < 0.45f || pose.position.y > 0.55f) {
    fprintf(stderr, "ball at y = %f\n", pose.position.y);
    return 8;
  }
  /* A bad def is rejected with a message naming the field. */
  ball.mass = -1.0f;
  if (vpColliderCreate(world, &ball, &ballId) != vpStatus_InvalidArgument) return 9;
  printf("c99 smoke: %s\n", vpGetLastError());
  /* C may pass any int as an enum: out-of-range values are rejected by name. */
  if (vpSetLogCallback(NULL, NULL, (vpLogLevel)17) != vpStatus_InvalidArgument) return 12;
  if (!strstr(vpGetLastError(), "minLevel = 17")) return 13;
  ball.mass = 1.0f;
  ball.bodyType = (vpBodyType)9;
  if (vpColliderCreate(world, &ball, &ballId) != vpStatus_InvalidArgument) return 14;
  if (!strstr(vpGetLastError(), "bodyType = 9")) return 15;
  /* A deformable from the library's box mesher: counts first, then the arrays. */
  if (vpBoxTetMesh(boxSize, boxCells, boxCorner, NULL, 0, NULL, 0, &boxVertexCount, &boxTetCount) != vpStatus_Ok ||
      boxVertexCount != 12 || boxTetCount != 12)
    return 21;
  if (vpBoxTetMesh(boxSize, boxCells, boxCorner, boxVertices, 12, boxTets, 12, NULL, NULL) != vpStatus_Ok) return 22;
  block.vertices = boxVertices;
  block.vertexCount = boxVertexCount;
  block.tets = boxTets;
  block.tetCount = boxTetCount;
  if (vpDeformableCreate(world, &block, &blockId) != vpStatus_Ok) return 23;
  /* A snapshot round trip: save, step on, restore; the step index is the saved one. */
  if (vpWorldSaveState(world, NULL, 0, &stateSize) != vpStatus_Ok) return 16;
  state = (unsigned char*)malloc(stateSize);
  if (!state || vpWorldSaveState(world, state, stateSize, &stateSize) != vpStatus_Ok) return 17;
  if (vpWorldStep(world, 1.0f / 60.0f) != vpStatus_Ok) return 18;
  if (vpWorldRestoreState(world, state, stateSize) != vpStatus_Ok) return 19;
  free(state);
  if (vpWorldGetStepStats(world, &stats) != vpStatus_Ok || stats.stepIndex != 120) return 20;
  /* Names are copied out with their terminator; an unnamed collider's is "". */
  if (vpColliderGetName(groundId, NULL, 0, &nameLength) != vpStatus_Ok || nameLength != 1) return 21;
  if (vpColliderGetName(groundId, name, (int32_t)sizeof name, &nameLength) != vpStatus_Ok || name[0] != '\0')
    return 22;
  if (vpWorldDestroy(world) != vpStatus_Ok) return 10;
  if (vpColliderGetPose(ballId, &pose) != vpStatus_InvalidId) return 11;
  return 0;
}
