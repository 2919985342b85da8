/* Everything the sample host draws or exports, read from a world through the C ABI: indexed
 * triangle meshes (collider shapes placed by a pose, deformable render meshes and liquid
 * surfaces in world space) and point sets (smoke). The renderer and the exporters take only
 * these two kinds, so a new actor needs only code that fills one. */
#ifndef VP_SAMPLE_SCENE_VIEW_H
#define VP_SAMPLE_SCENE_VIEW_H

#include "actor_labels.h"
#include "volphys/volphys.h"

typedef struct ViewMesh {
  char name[64];          /* the actor's label (actor_labels.h): file-name safe, used for exports */
  float color[4];
  int exported;           /* written by the mesh exporter (deformables: yes, colliders: no) */
  int framed;             /* counted by sceneViewBounds (not things that fly off or are unbounded) */
  vpTransform pose;       /* placement of positions/normals; identity for world-space meshes */
  float* positions;       /* xyz per vertex */
  float* normals;         /* xyz per vertex, unit */
  int32_t* triangles;     /* 3 vertex indices per triangle */
  int32_t vertexCount, triangleCount;
  int32_t vertexCapacity, triangleCapacity;
} ViewMesh;

typedef struct ViewPoints {
  char name[64];
  float pointSize;        /* pixels */
  float* xyz;             /* world space */
  float* rgba;            /* per point */
  int32_t count, capacity;
} ViewPoints;

typedef struct SceneView {
  ViewMesh* meshes;
  int meshCount, meshCapacity;
  ViewPoints* points;
  int pointsCount, pointsCapacity;
  /* Where each mesh comes from, parallel to meshes (all null for meshes added by others). */
  struct ViewMeshSource {
    vpColliderId collider;
    vpDeformableId deformable;
    vpFluidId fluid;
  } * sources;
  int sourcesCapacity;
  /* The smoke fluid each point set shows, parallel to points (null for sets added by others). */
  vpFluidId* pointSources;
  int pointSourcesCapacity;
  float* fieldScratch;    /* a fluid field copied out for the smoke points */
  int64_t fieldScratchCount;
} SceneView;

/* Builds meshes for every collider, deformable and liquid the labels list and point sets for
 * every smoke fluid, named by their labels. Returns 0 (with a message on stderr) if the ABI
 * refuses. */
int sceneViewInit(SceneView* view, const ActorLabels* labels);
/* Reads the current poses, deformed meshes, liquid surfaces and smoke. */
int sceneViewUpdate(SceneView* view);
/* Generic slots for other producers; the returned pointer is valid until the next add. Sizes
 * are grown with viewMeshReserve / viewPointsReserve. */
ViewMesh* sceneViewAddMesh(SceneView* view, const char* name, const float color[4], int exported);
ViewPoints* sceneViewAddPoints(SceneView* view, const char* name, float pointSize);
int viewMeshReserve(ViewMesh* mesh, int32_t vertexCount, int32_t triangleCount);
int viewPointsReserve(ViewPoints* points, int32_t count);
/* Centre and radius of a sphere around the meshes marked `framed`: what a camera should frame. */
void sceneViewBounds(const SceneView* view, float centre[3], float* radius);
void sceneViewFree(SceneView* view);

#endif
