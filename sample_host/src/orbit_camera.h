/* An orbit camera: looks at `target` from `distance` away, at `yaw` around the vertical axis
 * and `pitch` above the horizon (radians). The viewer drives it with the mouse; snapshots use
 * a fixed one framed on the scene. */
#ifndef VP_SAMPLE_ORBIT_CAMERA_H
#define VP_SAMPLE_ORBIT_CAMERA_H

typedef struct OrbitCamera {
  float target[3];
  float distance;
  float yaw, pitch;
  float fovYDegrees;
} OrbitCamera;

/* A three-quarter view of a sphere of `radius` around `centre`. */
OrbitCamera orbitCameraFraming(const float centre[3], float radius);
void orbitCameraRotate(OrbitCamera* c, float dYaw, float dPitch);
void orbitCameraZoom(OrbitCamera* c, float factor);
void orbitCameraEye(const OrbitCamera* c, float eye[3]);

#endif
