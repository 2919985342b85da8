#include "orbit_camera.h"

#include <math.h>

OrbitCamera orbitCameraFraming(const float centre[3], float radius) {
  OrbitCamera c;
  c.target[0] = centre[0];
  c.target[1] = centre[1];
  c.target[2] = centre[2];
  c.fovYDegrees = 45.0f;
  /* Far enough that the framing sphere fits the vertical field of view (it bounds the scene loosely). */
  c.distance = 1.0f * radius / sinf(0.5f * c.fovYDegrees * 3.14159265f / 180.0f);
  c.yaw = 0.6f;
  c.pitch = 0.6f; /* high enough to see into an open tank over its rim */
  return c;
}

void orbitCameraRotate(OrbitCamera* c, float dYaw, float dPitch) {
  c->yaw += dYaw;
  c->pitch += dPitch;
  /* Stay off the poles, where the up vector of the view would flip. */
  if (c->pitch > 1.5f) c->pitch = 1.5f;
  if (c->pitch < -1.5f) c->pitch = -1.5f;
}

void orbitCameraZoom(OrbitCamera* c, float factor) {
  c->distance *= factor;
  if (c->distance < 0.2f) c->distance = 0.2f;
  if (c->distance > 500.0f) c->distance = 500.0f;
}

void orbitCameraEye(const OrbitCamera* c, float eye[3]) {
  eye[0] = c->target[0] + c->distance * cosf(c->pitch) * sinf(c->yaw);
  eye[1] = c->target[1] + c->distance * sinf(c->pitch);
  eye[2] = c->target[2] + c->distance * cosf(c->pitch) * cosf(c->yaw);
}
