#include "offscreen_snapshot.h"

#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>

#include "png_writer.h"
#include "scene_renderer.h"

struct OffscreenSnapshot {
  OSMesaContext context;
  unsigned char* pixels;
  int width, height;
};

OffscreenSnapshot* offscreenSnapshotCreate(int width, int height) {
  OffscreenSnapshot* s = (OffscreenSnapshot*)calloc(1, sizeof *s);
  if (!s) return NULL;
  s->width = width;
  s->height = height;
  s->pixels = (unsigned char*)malloc((size_t)width * (size_t)height * 4);
  /* RGBA with a 24-bit depth buffer, no stencil or accumulation. */
  s->context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, NULL);
  if (!s->pixels || !s->context || !OSMesaMakeCurrent(s->context, s->pixels, GL_UNSIGNED_BYTE, width, height)) {
    fprintf(stderr, "snapshots: cannot create an OSMesa context of %dx%d\n", width, height);
    offscreenSnapshotDestroy(s);
    return NULL;
  }
  return s;
}

int offscreenSnapshotWrite(OffscreenSnapshot* s, const SceneView* view, const OrbitCamera* camera,
                           const char* const* overlay, int overlayLines, const char* path) {
  if (!OSMesaMakeCurrent(s->context, s->pixels, GL_UNSIGNED_BYTE, s->width, s->height)) return 0;
  renderScene(view, camera, s->width, s->height);
  if (overlayLines > 0) renderOverlayText(overlay, overlayLines, s->width, s->height);
  glFinish();
  /* OSMesa's buffer starts with the bottom row, like glReadPixels. */
  return pngWriteRgba(path, s->width, s->height, s->pixels, 1);
}

void offscreenSnapshotDestroy(OffscreenSnapshot* s) {
  if (!s) return;
  if (s->context) OSMesaDestroyContext(s->context);
  free(s->pixels);
  free(s);
}
