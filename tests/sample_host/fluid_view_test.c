/* The sample host's view of fluids, through the C ABI only: a liquid becomes an exported
 * surface mesh inside its domain, smoke a bounded set of translucent points where the smoke is.
 * Exit code: the number of failed checks. */
#include <stdio.h>
#include <string.h>

#include "actor_labels.h"
#include "fluid_view.h"
#include "scene_view.h"

static int failures = 0;

static void check(int ok, const char* what) {
  if (!ok) {
    printf("FAIL: %s\n", what);
    ++failures;
  }
}

static vpFluidId makeFluid(vpWorldId world, vpFluidKind kind, float x0, int n, float h) {
  vpFluidDef def = vpDefaultFluidDef();
  vpFluidRegion tank;
  vpFluidEmitter emitter;
  vpFluidId id = {0, 0, {0, 0}};
  def.kind = kind;
  def.origin.x = x0;
  def.resolution[0] = def.resolution[1] = def.resolution[2] = n;
  def.cellSize = h;
  tank.type = vpRegionType_Box;
  tank.centre.x = x0 + 0.5f * n * h;
  tank.centre.y = 0.25f * n * h;
  tank.centre.z = 0.5f * n * h;
  tank.halfExtents = tank.centre;
  tank.halfExtents.x = 0.5f * n * h;
  tank.radius = 0.0f;
  emitter.region.type = vpRegionType_Sphere;
  emitter.region.centre = tank.centre;
  emitter.region.radius = 3.0f * h;
  emitter.region.halfExtents = tank.halfExtents;
  emitter.velocity.x = emitter.velocity.z = 0.0f;
  emitter.velocity.y = 0.5f;
  emitter.densityRate = 2.0f;
  emitter.temperature = 2.0f;
  if (kind == vpFluidKind_Liquid) {
    def.initialLiquid = &tank;
    def.initialLiquidCount = 1;
  } else {
    def.emitters = &emitter;
    def.emitterCount = 1;
  }
  if (vpFluidCreate(world, &def, &id) != vpStatus_Ok) printf("vpFluidCreate: %s\n", vpGetLastError());
  return id;
}

int main(void) {
  const float h = 1.0f / 16.0f;
  const int n = 49; /* more cells than the point budget, and odd, so the subsampling rounds up */
  vpWorldDef def = vpDefaultWorldDef();
  vpWorldId world;
  ActorLabels labels;
  SceneView view;
  int i, inside = 1;
  def.frameBudgetMs = 0.0f;
  if (vpWorldCreate(&def, &world) != vpStatus_Ok) return 1;
  makeFluid(world, vpFluidKind_Smoke, -4.0f, n, h);
  makeFluid(world, vpFluidKind_Liquid, 0.0f, 12, h);
  for (i = 0; i < 4; ++i) vpWorldStep(world, 1.0f / 60.0f);

  check(actorLabelsInit(&labels, world), "actorLabelsInit");
  check(sceneViewInit(&view, &labels), "sceneViewInit");
  check(view.meshCount == 1 && view.pointsCount == 1, "one surface mesh (liquid) and one point set (smoke)");
  if (view.meshCount == 1) {
    const ViewMesh* m = &view.meshes[0];
    check(m->exported && m->triangleCount > 0, "the liquid surface is an exported, non-empty mesh");
    check(strcmp(m->name, "fluid1") == 0, "an unnamed liquid is named by its place in the world's list: fluid1");
    for (i = 0; i < 3 * m->vertexCount; ++i)
      if (m->positions[i] < -h || m->positions[i] > 13.0f * h) inside = 0;
    check(inside, "the liquid surface lies in its domain (world space)");
  }
  if (view.pointsCount == 1) {
    const ViewPoints* p = &view.points[0];
    int translucent = 1;
    inside = 1;
    check(p->count > 0, "smoke points where the emitter is");
    check(p->count <= FLUID_VIEW_MAX_SMOKE_POINTS, "the smoke points stay within the budget");
    for (i = 0; i < p->count; ++i) {
      const float* x = &p->xyz[3 * i];
      if (x[0] < -4.0f || x[0] > -4.0f + n * h || x[1] < 0.0f || x[1] > n * h) inside = 0;
      if (p->rgba[4 * i + 3] <= 0.0f || p->rgba[4 * i + 3] >= 1.0f) translucent = 0;
    }
    check(inside, "smoke points lie in the smoke's domain");
    check(translucent, "smoke points are translucent");
  }
  check(sceneViewUpdate(&view), "sceneViewUpdate after another step");
  sceneViewFree(&view);
  actorLabelsFree(&labels);
  vpWorldDestroy(world);
  printf("%s\n", failures ? "fluid view: FAILED" : "fluid view OK");
  return failures;
}
