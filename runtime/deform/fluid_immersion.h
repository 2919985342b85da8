// A deformable in the fluids: its boundary as a solid the fluids see, and their pressure on it.
//
// The fluids take the boundary triangles of the tet mesh (the corner nodes' triangles; for
// quadratic and cubic elements the flat triangles under the curved surface) at the current
// node positions, with the node velocities, as a moving closed mesh (collide/face_coverage.h,
// deforming surfaces): exact face fractions, and on each face it cuts the surface's velocity
// where it crosses the face (fluid/solids/face_fraction_field.h has the rules for the faces it
// covers whole). What a fluid's step sees stays as it was while the
// step runs over several frames (the surface is copied before it changes while shared).
//
// Each fluid's last completed step leaves a force on every surface vertex
// (fluid/solids/surface_pressure_load.h); they act on the vertices' nodes through the steps
// that follow until the next one completes, one step late like the rigid bodies' loads. The
// delay would make a light body unstable (the pressure carries the reaction of the fluid it
// accelerates, its added mass m_a, one step late), so the loads are stabilized as a rigid
// body's are (collide/collider.cpp). The vertex forces split into their rigid part, the net
// force F and torque tau about the centre of mass spread over the nodes as a rigid motion
// (f_i = m_i (F / m + I^-1 tau x r_i), which strains nothing), and the rest, which has no net
// force or torque. With m the body's mass and k = m_a / m, the rigid part becomes
//     F' = (F + m_a (a_last - g)) / (1 + k),   tau' = (tau + k I alpha_last) / (1 + k),
// where a_last and alpha_last are the last step's changes of the centre of mass's velocity
// and of the body's spin (angular momentum over inertia) over that step's length (which is
// not the coming step's when a frame budget changes the body's rate); the rest is scaled by
// 1 / (1 + k) too.
#pragma once

#include <cstdint>
#include <memory>

#include "collide/face_coverage.h"
#include "core/allocator.h"
#include "core/math_types.h"
#include "core/status.h"
#include "geometry/surface_mesh.h"

namespace vp {

class FluidImmersion {
 public:
  // `boundary`'s vertex v is node vertexNode[v]; x holds 3 coordinates per node.
  Status build(const SurfaceMesh& boundary, const Array<int32_t>& vertexNode, const Array<double>& x);

  // The surface at positions x and velocities v (3 per node); it moves (a new surfaceMoves)
  // only when one of its vertices did.
  std::shared_ptr<const PreparedCollider> surface(const Array<double>& x, const Array<double>& v);

  // The loads of the fluids' last completed steps on this body: cleared, then added one by one
  // (a load whose vertex count is not this surface's is ignored and returns false).
  void clearLoads();
  bool addLoad(const Array<Vec3>& vertexForces, double addedMass);
  bool loaded() const { return loaded_; }

  // At the start of every step of the body, of length h: remembers how fast its centre-of-mass
  // velocity and its spin changed in the last one.
  void trackVelocity(const Array<double>& x, const Array<double>& v, const Array<double>& mass, double h);
  // The loads as node forces for a step of h under gravity g, added to `force` (3 per node).
  // Nodes touching a collider (touching[node] != 0) take no vertex force: the fluid between two
  // solids closer than a cell is not resolved (its pressure there swings with the gap, and
  // one step late it launches the body), and the contact carries the load there.
  void addNodeForces(const Array<double>& x, const Array<double>& mass, double h, const Vec3& gravity,
                     const Array<uint8_t>& touching, Array<double>* force) const;

  // What evolves with the body (its saved state): the velocity and spin at the start of the
  // step now running, that step's length, and their rates of change over the step before.
  struct Tracking {
    Vec3 velocity = Vec3::Zero(), acceleration = Vec3::Zero();
    Vec3 spin = Vec3::Zero(), spinAcceleration = Vec3::Zero();
    double stepDt = 0.0;
  };
  const Tracking& tracking() const { return tracking_; }
  void restoreTracking(const Tracking& tracking) { tracking_ = tracking; }

 private:
  Array<int32_t> vertexNode_;
  std::shared_ptr<PreparedCollider> surface_;
  Array<Eigen::Vector3d> positions_, velocities_;  // scratch
  Array<Vec3> forces_;
  double addedMass_ = 0.0;
  bool loaded_ = false;
  Tracking tracking_;
};

}  // namespace vp
