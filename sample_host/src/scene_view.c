#include "scene_view.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fluid_view.h"

static const vpTransform kIdentity = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f, 1.0f}};

static int report(const char* what, vpStatus s) {
  fprintf(stderr, "scene view: %s failed (%s): %s\n", what, vpStatusName(s), vpGetLastError());
  return 0;
}

static int grow(void** items, int* capacity, int needed, size_t itemSize) {
  void* p;
  int cap = *capacity ? *capacity : 8;
  if (needed <= *capacity) return 1;
  while (cap < needed) cap *= 2;
  p = realloc(*items, (size_t)cap * itemSize);
  if (!p) return 0;
  memset((char*)p + (size_t)*capacity * itemSize, 0, (size_t)(cap - *capacity) * itemSize);
  *items = p;
  *capacity = cap;
  return 1;
}

int viewMeshReserve(ViewMesh* m, int32_t vertexCount, int32_t triangleCount) {
  if (vertexCount > m->vertexCapacity) {
    float* p = (float*)realloc(m->positions, sizeof(float) * 3 * (size_t)vertexCount);
    float* n;
    if (!p) return 0;
    m->positions = p;
    n = (float*)realloc(m->normals, sizeof(float) * 3 * (size_t)vertexCount);
    if (!n) return 0;
    m->normals = n;
    m->vertexCapacity = vertexCount;
  }
  if (triangleCount > m->triangleCapacity) {
    int32_t* t = (int32_t*)realloc(m->triangles, sizeof(int32_t) * 3 * (size_t)triangleCount);
    if (!t) return 0;
    m->triangles = t;
    m->triangleCapacity = triangleCount;
  }
  return 1;
}

int viewPointsReserve(ViewPoints* p, int32_t count) {
  if (count > p->capacity) {
    float* xyz = (float*)realloc(p->xyz, sizeof(float) * 3 * (size_t)count);
    float* rgba;
    if (!xyz) return 0;
    p->xyz = xyz;
    rgba = (float*)realloc(p->rgba, sizeof(float) * 4 * (size_t)count);
    if (!rgba) return 0;
    p->rgba = rgba;
    p->capacity = count;
  }
  return 1;
}

ViewMesh* sceneViewAddMesh(SceneView* v, const char* name, const float color[4], int exported) {
  ViewMesh* m;
  if (!grow((void**)&v->meshes, &v->meshCapacity, v->meshCount + 1, sizeof(ViewMesh))) return NULL;
  if (!grow((void**)&v->sources, &v->sourcesCapacity, v->meshCount + 1, sizeof *v->sources)) return NULL;
  m = &v->meshes[v->meshCount++];
  memset(m, 0, sizeof *m);
  snprintf(m->name, sizeof m->name, "%s", name);
  memcpy(m->color, color, sizeof m->color);
  m->exported = exported;
  m->framed = 1;
  m->pose = kIdentity;
  return m;
}

ViewPoints* sceneViewAddPoints(SceneView* v, const char* name, float pointSize) {
  ViewPoints* p;
  if (!grow((void**)&v->points, &v->pointsCapacity, v->pointsCount + 1, sizeof(ViewPoints))) return NULL;
  if (!grow((void**)&v->pointSources, &v->pointSourcesCapacity, v->pointsCount + 1, sizeof *v->pointSources))
    return NULL;
  p = &v->points[v->pointsCount++];
  memset(p, 0, sizeof *p);
  snprintf(p->name, sizeof p->name, "%s", name);
  p->pointSize = pointSize;
  return p;
}

static void colliderColor(vpBodyType type, float out[4]) {
  /* Static grey, kinematic (host-driven) orange, dynamic blue: the reader sees who moves whom. */
  static const float colors[3][4] = {{0.55f, 0.57f, 0.6f, 1}, {0.95f, 0.55f, 0.15f, 1}, {0.25f, 0.5f, 0.9f, 1}};
  memcpy(out, colors[(int)type >= 0 && (int)type < 3 ? (int)type : 0], sizeof colors[0]);
}

static int addColliders(SceneView* v, const ActorLabels* labels) {
  int i;
  vpStatus s = vpStatus_Ok;
  for (i = 0; i < labels->colliderCount; ++i) {
    const vpColliderId id = labels->colliders[i];
    float color[4];
    vpBodyType type = vpBodyType_Static;
    int32_t nv = 0, nt = 0;
    ViewMesh* m;
    vpColliderGetBodyType(id, &type);
    colliderColor(type, color);
    if ((s = vpColliderGetShapeMeshSize(id, &nv, &nt)) != vpStatus_Ok) break;
    if (!(m = sceneViewAddMesh(v, labels->colliderLabels[i], color, 0)) || !viewMeshReserve(m, nv, nt)) return 0;
    v->sources[v->meshCount - 1].collider = id;
    /* Frame what stays put: dynamic bodies start high and fall in, and a plane (the only
     * shape whose mesh is a single quad) is unbounded. */
    m->framed = type != vpBodyType_Dynamic && !(nv == 4 && nt == 2);
    if ((s = vpColliderGetShapeMesh(id, m->positions, m->normals, nv, m->triangles, nt)) != vpStatus_Ok) break;
    m->vertexCount = nv;
    m->triangleCount = nt;
  }
  if (s != vpStatus_Ok) return report("collider shape mesh", s);
  return 1;
}

static int addDeformables(SceneView* v, const ActorLabels* labels) {
  static const float jelly[4] = {0.35f, 0.8f, 0.35f, 1.0f};
  int i;
  for (i = 0; i < labels->deformableCount; ++i) {
    if (!sceneViewAddMesh(v, labels->deformableLabels[i], jelly, 1)) return 0;
    v->sources[v->meshCount - 1].deformable = labels->deformables[i];
  }
  return 1;
}

/* A liquid becomes a surface mesh, smoke a point set, each under the fluid's label. */
static int addFluids(SceneView* v, const ActorLabels* labels) {
  static const float water[4] = {0.2f, 0.45f, 0.85f, 1.0f};
  int i;
  vpStatus s;
  for (i = 0; i < labels->fluidCount; ++i) {
    vpFluidKind kind = vpFluidKind_Smoke;
    if ((s = vpFluidGetKind(labels->fluids[i], &kind)) != vpStatus_Ok) return report("vpFluidGetKind", s);
    if (kind == vpFluidKind_Liquid) {
      if (!sceneViewAddMesh(v, labels->fluidLabels[i], water, 1)) return 0;
      v->sources[v->meshCount - 1].fluid = labels->fluids[i];
    } else {
      if (!sceneViewAddPoints(v, labels->fluidLabels[i], 4.0f)) return 0;
      v->pointSources[v->pointsCount - 1] = labels->fluids[i];
    }
  }
  return 1;
}

int sceneViewInit(SceneView* v, const ActorLabels* labels) {
  memset(v, 0, sizeof *v);
  return addColliders(v, labels) && addDeformables(v, labels) && addFluids(v, labels) && sceneViewUpdate(v);
}

int sceneViewUpdate(SceneView* v) {
  int i;
  vpStatus s;
  for (i = 0; i < v->meshCount; ++i) {
    ViewMesh* m = &v->meshes[i];
    const vpColliderId collider = v->sources[i].collider;
    const vpDeformableId deformable = v->sources[i].deformable;
    const vpFluidId fluid = v->sources[i].fluid;
    if (!vpColliderIdIsNull(collider)) {
      if ((s = vpColliderGetPose(collider, &m->pose)) != vpStatus_Ok) return report("vpColliderGetPose", s);
    } else if (!vpDeformableIdIsNull(deformable)) {
      int32_t nv = 0, nt = 0;
      if ((s = vpDeformableGetRenderMeshSize(deformable, &nv, &nt)) != vpStatus_Ok)
        return report("vpDeformableGetRenderMeshSize", s);
      if (!viewMeshReserve(m, nv, nt)) return 0;
      if ((s = vpDeformableGetRenderMesh(deformable, m->positions, m->normals, nv, m->triangles, nt)) !=
          vpStatus_Ok)
        return report("vpDeformableGetRenderMesh", s);
      m->vertexCount = nv;
      m->triangleCount = nt;
    } else if (!vpFluidIdIsNull(fluid) && !fluidViewReadSurface(m, fluid)) {
      return 0;
    }
  }
  for (i = 0; i < v->pointsCount; ++i)
    if (!vpFluidIdIsNull(v->pointSources[i]) &&
        !fluidViewReadSmoke(&v->points[i], v->pointSources[i], &v->fieldScratch, &v->fieldScratchCount))
      return 0;
  return 1;
}

static void rotate(const vpQuat* q, const float in[3], float out[3]) {
  /* v' = v + 2w (u x v) + 2 u x (u x v), u = (x, y, z) */
  float tx = 2.0f * (q->y * in[2] - q->z * in[1]);
  float ty = 2.0f * (q->z * in[0] - q->x * in[2]);
  float tz = 2.0f * (q->x * in[1] - q->y * in[0]);
  out[0] = in[0] + q->w * tx + (q->y * tz - q->z * ty);
  out[1] = in[1] + q->w * ty + (q->z * tx - q->x * tz);
  out[2] = in[2] + q->w * tz + (q->x * ty - q->y * tx);
}

void sceneViewBounds(const SceneView* v, float centre[3], float* radius) {
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  int i, k, any = 0;
  int32_t j;
  for (i = 0; i < v->meshCount; ++i) {
    const ViewMesh* m = &v->meshes[i];
    if (!m->framed) continue;
    for (j = 0; j < m->vertexCount; ++j) {
      float p[3];
      rotate(&m->pose.rotation, &m->positions[3 * j], p);
      p[0] += m->pose.position.x;
      p[1] += m->pose.position.y;
      p[2] += m->pose.position.z;
      for (k = 0; k < 3; ++k) {
        if (p[k] < lo[k]) lo[k] = p[k];
        if (p[k] > hi[k]) hi[k] = p[k];
      }
      any = 1;
    }
  }
  if (!any) {
    centre[0] = centre[1] = centre[2] = 0.0f;
    *radius = 5.0f;
    return;
  }
  for (k = 0; k < 3; ++k) centre[k] = 0.5f * (lo[k] + hi[k]);
  *radius = 0.5f * sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                         (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (*radius < 0.5f) *radius = 0.5f;
}

void sceneViewFree(SceneView* v) {
  int i;
  for (i = 0; i < v->meshCount; ++i) {
    free(v->meshes[i].positions);
    free(v->meshes[i].normals);
    free(v->meshes[i].triangles);
  }
  for (i = 0; i < v->pointsCount; ++i) {
    free(v->points[i].xyz);
    free(v->points[i].rgba);
  }
  free(v->meshes);
  free(v->points);
  free(v->sources);
  free(v->pointSources);
  free(v->fieldScratch);
  memset(v, 0, sizeof *v);
}
