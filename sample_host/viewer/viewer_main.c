/* VolPhys viewer: the sample host's scene in a window (GLFW + OpenGL). Drag with the left
 * button to orbit, scroll to zoom, space to pause, N to step once while paused, R to re-frame,
 * Esc or Q to quit. The last step's budget and per-phase timings are drawn on screen. With
 * --frames N it quits after N steps, and --screenshot PATH saves the last frame as a PNG
 * (what the Xvfb test checks). Drawing is shared with the headless host's snapshots. */
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "actor_labels.h"
#include "cli_values.h"
#include "default_scene.h"
#include "hud_stats.h"
#include "orbit_camera.h"
#include "png_writer.h"
#include "scene_renderer.h"
#include "scene_view.h"
#include "volphys/volphys.h"

typedef struct Viewer {
  OrbitCamera camera, framing;
  int paused, stepOnce, dragging;
  double lastX, lastY;
} Viewer;

static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods) {
  Viewer* v = (Viewer*)glfwGetWindowUserPointer(window);
  (void)scancode;
  (void)mods;
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  if (key == GLFW_KEY_SPACE && action == GLFW_PRESS) v->paused = !v->paused;
  else if (key == GLFW_KEY_N || key == GLFW_KEY_RIGHT) v->stepOnce = 1;
  else if (key == GLFW_KEY_R) v->camera = v->framing;
  else if (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q) glfwSetWindowShouldClose(window, GLFW_TRUE);
}

static void onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  Viewer* v = (Viewer*)glfwGetWindowUserPointer(window);
  (void)mods;
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  v->dragging = action == GLFW_PRESS;
  glfwGetCursorPos(window, &v->lastX, &v->lastY);
}

static void onCursor(GLFWwindow* window, double x, double y) {
  Viewer* v = (Viewer*)glfwGetWindowUserPointer(window);
  if (!v->dragging) return;
  orbitCameraRotate(&v->camera, -0.008f * (float)(x - v->lastX), 0.008f * (float)(y - v->lastY));
  v->lastX = x;
  v->lastY = y;
}

static void onScroll(GLFWwindow* window, double dx, double dy) {
  Viewer* v = (Viewer*)glfwGetWindowUserPointer(window);
  (void)dx;
  orbitCameraZoom(&v->camera, dy > 0 ? 0.9f : 1.0f / 0.9f);
}

static int fail(const char* what, vpStatus s) {
  fprintf(stderr, "volphys_viewer: %s failed (%s): %s\n", what, vpStatusName(s), vpGetLastError());
  return 1;
}

static int screenshot(const char* path, int width, int height) {
  unsigned char* pixels = (unsigned char*)malloc((size_t)width * (size_t)height * 4);
  int ok;
  if (!pixels) return 0;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  ok = pngWriteRgba(path, width, height, pixels, 1);
  free(pixels);
  return ok;
}

static void usage(FILE* f) {
  fprintf(f,
          "usage: volphys_viewer [--scene FILE] [--dt SECONDS] [--workers N] [--budget MS] [--size WxH]\n"
          "                      [--frames N] [--screenshot PNG]\n"
          "Keys: drag = orbit, scroll = zoom, space = pause, N = single step, R = re-frame, Esc/Q = quit.\n"
          "--frames N quits after N steps (0: run until closed); --screenshot saves the last frame.\n");
}

static const char* const kProgram = "volphys_viewer";

int main(int argc, char** argv) {
  const char* scenePath = defaultScenePath();
  const char* shotPath = NULL;
  double dt = 1.0 / 60.0, budget = -1.0;
  int workers = 2, frames = 0, width = 960, height = 640, steps = 0, i;
  vpWorldDef def;
  vpWorldId world;
  vpStatus s;
  ActorLabels labels;
  SceneView view;
  Viewer v;
  GLFWwindow* window;
  float centre[3], radius;

  for (i = 1; i < argc; ++i) {
    const char* a = argv[i];
    const char* val = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      usage(stdout);
      return 0;
    }
    if (!val) {
      fprintf(stderr, "volphys_viewer: %s needs a value\n", a);
      return 2;
    }
    ++i;
    if (!strcmp(a, "--scene")) scenePath = val;
    else if (!strcmp(a, "--screenshot")) shotPath = val;
    else if (!strcmp(a, "--dt")) { if (!cliDouble(kProgram, a, val, 1e-5, 1.0, &dt)) return 2; }
    else if (!strcmp(a, "--budget")) { if (!cliDouble(kProgram, a, val, 0.0, 1e4, &budget)) return 2; }
    else if (!strcmp(a, "--workers")) { if (!cliInt(kProgram, a, val, 1, 64, &workers)) return 2; }
    else if (!strcmp(a, "--frames")) { if (!cliInt(kProgram, a, val, 0, 10000000, &frames)) return 2; }
    else if (!strcmp(a, "--size")) { if (!cliSize(kProgram, a, val, 16, 8192, &width, &height)) return 2; }
    else {
      fprintf(stderr, "%s: unknown option '%s'\n", kProgram, a);
      usage(stderr);
      return 2;
    }
  }

  if ((s = vpCheckVersion()) != vpStatus_Ok) return fail("version check", s);
  def = vpDefaultWorldDef();
  def.workerCount = workers;
  if ((s = vpWorldCreate(&def, &world)) != vpStatus_Ok) return fail("vpWorldCreate", s);
  if ((s = vpWorldLoadScene(world, scenePath)) != vpStatus_Ok) return fail("vpWorldLoadScene", s);
  if (budget >= 0.0 && (s = vpWorldSetFrameBudget(world, (float)budget)) != vpStatus_Ok)
    return fail("vpWorldSetFrameBudget", s);
  if (!actorLabelsInit(&labels, world) || !sceneViewInit(&view, &labels)) return 1;

  if (!glfwInit()) {
    fprintf(stderr, "volphys_viewer: glfwInit failed (no display? run under xvfb-run)\n");
    return 1;
  }
  window = glfwCreateWindow(width, height, "VolPhys viewer", NULL, NULL);
  if (!window) {
    fprintf(stderr, "volphys_viewer: cannot create an OpenGL window\n");
    glfwTerminate();
    return 1;
  }
  memset(&v, 0, sizeof v);
  sceneViewBounds(&view, centre, &radius);
  v.camera = v.framing = orbitCameraFraming(centre, radius);
  glfwSetWindowUserPointer(window, &v);
  glfwSetKeyCallback(window, onKey);
  glfwSetMouseButtonCallback(window, onMouseButton);
  glfwSetCursorPosCallback(window, onCursor);
  glfwSetScrollCallback(window, onScroll);
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);

  while (!glfwWindowShouldClose(window)) {
    char lines[HUD_MAX_LINES + 1][HUD_LINE_CHARS];
    const char* pointers[HUD_MAX_LINES + 1];
    int n, fbWidth, fbHeight, last;
    if (!v.paused || v.stepOnce) {
      if ((s = vpWorldStep(world, (float)dt)) != vpStatus_Ok) return fail("vpWorldStep", s);
      ++steps;
      v.stepOnce = 0;
      if (!sceneViewUpdate(&view)) return 1;
    }
    last = frames > 0 && steps >= frames;
    glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
    renderScene(&view, &v.camera, fbWidth, fbHeight);
    n = hudStatsLines(world, &labels, lines);
    snprintf(lines[n++], HUD_LINE_CHARS, "%s[space] pause  [n] step  [drag] orbit  [scroll] zoom  [r] reset  [q] quit",
             v.paused ? "PAUSED  " : "");
    for (i = 0; i < n; ++i) pointers[i] = lines[i];
    renderOverlayText(pointers, n, fbWidth, fbHeight);
    if (last && shotPath) {
      if (!screenshot(shotPath, fbWidth, fbHeight)) return 1;
      printf("volphys_viewer: wrote %s (%dx%d) after %d steps\n", shotPath, fbWidth, fbHeight, steps);
    }
    glfwSwapBuffers(window);
    glfwPollEvents();
    if (last) break;
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  sceneViewFree(&view);
  actorLabelsFree(&labels);
  vpWorldDestroy(world);
  return 0;
}
