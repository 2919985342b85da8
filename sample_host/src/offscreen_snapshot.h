/* PNG snapshots without a display: an OSMesa context (Mesa's software renderer drawing into
 * our own memory) runs the same renderer as the viewer. Headless CI has no X server, and
 * OSMesa needs none. */
#ifndef VP_SAMPLE_OFFSCREEN_SNAPSHOT_H
#define VP_SAMPLE_OFFSCREEN_SNAPSHOT_H

#include "orbit_camera.h"
#include "scene_view.h"

typedef struct OffscreenSnapshot OffscreenSnapshot;

/* NULL (with a message on stderr) if no context can be made. */
OffscreenSnapshot* offscreenSnapshotCreate(int width, int height);
/* Renders the view with the camera and the overlay lines, writes a PNG. Returns 1 on success. */
int offscreenSnapshotWrite(OffscreenSnapshot* s, const SceneView* view, const OrbitCamera* camera,
                           const char* const* overlay, int overlayLines, const char* path);
void offscreenSnapshotDestroy(OffscreenSnapshot* s);

#endif
