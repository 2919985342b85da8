#include "scene_renderer.h"

#include <GL/gl.h>
#include <math.h>
#include <string.h>

/* A public-domain vector font in one header (Debian's libstb-dev): text without textures. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include "overlay_layout.h"

static void lookAt(const float eye[3], const float target[3]) {
  /* Builds the view matrix directly (no GLU): rows are the camera's right, up, back axes. */
  float f[3], s[3], u[3], n;
  float m[16];
  int k;
  for (k = 0; k < 3; ++k) f[k] = target[k] - eye[k];
  n = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (k = 0; k < 3; ++k) f[k] /= n;
  s[0] = f[1] * 0.0f - f[2] * 1.0f; /* f x (0, 1, 0) */
  s[1] = f[2] * 0.0f - f[0] * 0.0f;
  s[2] = f[0] * 1.0f - f[1] * 0.0f;
  n = sqrtf(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (k = 0; k < 3; ++k) s[k] /= n;
  u[0] = s[1] * f[2] - s[2] * f[1];
  u[1] = s[2] * f[0] - s[0] * f[2];
  u[2] = s[0] * f[1] - s[1] * f[0];
  memset(m, 0, sizeof m);
  for (k = 0; k < 3; ++k) {
    m[4 * k + 0] = s[k];
    m[4 * k + 1] = u[k];
    m[4 * k + 2] = -f[k];
  }
  m[15] = 1.0f;
  glMultMatrixf(m);
  glTranslatef(-eye[0], -eye[1], -eye[2]);
}

static void applyPose(const vpTransform* t) {
  const vpQuat* q = &t->rotation;
  float m[16];
  m[0] = 1 - 2 * (q->y * q->y + q->z * q->z);
  m[1] = 2 * (q->x * q->y + q->z * q->w);
  m[2] = 2 * (q->x * q->z - q->y * q->w);
  m[3] = 0;
  m[4] = 2 * (q->x * q->y - q->z * q->w);
  m[5] = 1 - 2 * (q->x * q->x + q->z * q->z);
  m[6] = 2 * (q->y * q->z + q->x * q->w);
  m[7] = 0;
  m[8] = 2 * (q->x * q->z + q->y * q->w);
  m[9] = 2 * (q->y * q->z - q->x * q->w);
  m[10] = 1 - 2 * (q->x * q->x + q->y * q->y);
  m[11] = 0;
  m[12] = t->position.x;
  m[13] = t->position.y;
  m[14] = t->position.z;
  m[15] = 1;
  glMultMatrixf(m);
}

static void setUpLights(void) {
  static const float direction[4] = {0.4f, 1.0f, 0.6f, 0.0f}; /* w = 0: directional */
  static const float diffuse[4] = {0.8f, 0.8f, 0.8f, 1.0f};
  static const float ambient[4] = {0.3f, 0.3f, 0.32f, 1.0f};
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glLightfv(GL_LIGHT0, GL_POSITION, direction);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  /* Open meshes and planes are seen from both sides. */
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  glEnable(GL_COLOR_MATERIAL);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glEnable(GL_NORMALIZE);
}

static void drawMesh(const ViewMesh* m) {
  if (m->triangleCount <= 0) return;
  glPushMatrix();
  applyPose(&m->pose);
  glColor4fv(m->color);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, m->positions);
  glNormalPointer(GL_FLOAT, 0, m->normals);
  glDrawElements(GL_TRIANGLES, 3 * m->triangleCount, GL_UNSIGNED_INT, m->triangles);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glPopMatrix();
}

static void drawPoints(const ViewPoints* p) {
  if (p->count <= 0) return;
  glDisable(GL_LIGHTING);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE); /* translucent: do not hide what is drawn after */
  glPointSize(p->pointSize);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, p->xyz);
  glColorPointer(4, GL_FLOAT, 0, p->rgba);
  glDrawArrays(GL_POINTS, 0, p->count);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glEnable(GL_LIGHTING);
}

void renderScene(const SceneView* view, const OrbitCamera* camera, int width, int height) {
  const float nearZ = 0.05f, farZ = 1000.0f;
  float eye[3], top;
  int i;
  glViewport(0, 0, width, height);
  glClearColor(0.12f, 0.13f, 0.16f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  top = nearZ * tanf(0.5f * camera->fovYDegrees * 3.14159265f / 180.0f);
  glFrustum(-top * width / height, top * width / height, -top, top, nearZ, farZ);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  orbitCameraEye(camera, eye);
  lookAt(eye, camera->target);
  setUpLights();
  for (i = 0; i < view->meshCount; ++i) drawMesh(&view->meshes[i]);
  for (i = 0; i < view->pointsCount; ++i) drawPoints(&view->points[i]);
  glDisable(GL_LIGHTING);
}

void renderOverlayText(const char* const* lines, int lineCount, int width, int height) {
  static char quads[60000]; /* stb_easy_font: ~270 bytes per character */
  static OverlayLayout layout;
  int i;
  overlayLayout(lines, lineCount, width, &layout);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, width, height, 0, -1, 1); /* y down, as stb_easy_font writes */
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glEnableClientState(GL_VERTEX_ARRAY);
  for (i = 0; i < layout.lineCount; ++i) {
    int n;
    glPushMatrix();
    glTranslatef(OVERLAY_MARGIN_PX, OVERLAY_MARGIN_PX + 12.0f * layout.scale * (float)i, 0.0f);
    glScalef(layout.scale, layout.scale, 1.0f);
    n = stb_easy_font_print(0, 0, layout.lines[i], NULL, quads, (int)sizeof quads);
    glColor3f(0.95f, 0.95f, 0.85f);
    glVertexPointer(2, GL_FLOAT, 16, quads);
    glDrawArrays(GL_QUADS, 0, 4 * n);
    glPopMatrix();
  }
  glDisableClientState(GL_VERTEX_ARRAY);
  glEnable(GL_DEPTH_TEST);
}
