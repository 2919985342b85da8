/* A program outside the VolPhys tree, built against an installed VolPhys (find_package or
 * pkg-config): it creates a world with a falling ball, steps it and checks it fell. */
#include <stdio.h>

#include <volphys/volphys.h>

int main(void) {
  vpWorldDef def = vpDefaultWorldDef();
  vpColliderDef ball = vpDefaultColliderDef();
  vpWorldId world;
  vpColliderId id;
  vpTransform pose;
  int i;
  if (vpCheckVersion() != vpStatus_Ok) return 1;
  def.frameBudgetMs = 0.0f;
  if (vpWorldCreate(&def, &world) != vpStatus_Ok) return 2;
  ball.bodyType = vpBodyType_Dynamic;
  ball.pose.position.y = 10.0f;
  if (vpColliderCreate(world, &ball, &id) != vpStatus_Ok) return 3;
  for (i = 0; i < 30; ++i)
    if (vpWorldStep(world, 1.0f / 60.0f) != vpStatus_Ok) return 4;
  if (vpColliderGetPose(id, &pose) != vpStatus_Ok || !(pose.position.y < 9.0f)) return 5;
  vpWorldDestroy(world);
  printf("consumer: VolPhys %d.%d, the ball fell to y = %.2f\n", VP_VERSION_MAJOR, VP_VERSION_MINOR, pose.position.y);
  return 0;
}
