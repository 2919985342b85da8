/* Draws a SceneView with fixed-function OpenGL (1.x vertex arrays and lighting), which both
 * the viewer's GLFW window and the offscreen OSMesa context provide, including Mesa's
 * software renderers under Xvfb. The caller owns the GL context and makes it current. */
#ifndef VP_SAMPLE_SCENE_RENDERER_H
#define VP_SAMPLE_SCENE_RENDERER_H

#include "orbit_camera.h"
#include "scene_view.h"

void renderScene(const SceneView* view, const OrbitCamera* camera, int width, int height);
/* Text lines in the top-left corner, drawn over whatever is there (stb_easy_font quads). */
void renderOverlayText(const char* const* lines, int lineCount, int width, int height);

#endif
