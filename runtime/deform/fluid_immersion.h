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
// A liquid's pressure on the surface splits in two (fluid/solids/surface_pressure_load.h): the
// hydrostatic part, which depends only on where the surface is under the liquid's free surface,
// is taken anew at every step of the body from the liquid's last level set; the rest, the
// dynamic part, is known only at the fluid's steps. Each fluid's last completed step leaves
// that part on every surface vertex, acting on the vertices' nodes through the steps that
// follow until the next one completes, one step late like the rigid bodies' loads. A fluid
// step may span several frames under a frame budget, and a buoyancy held that long is a
// delayed spring: it pumps a floating body's bobbing up, and a body falling in meets no
// liquid until the step completes.
// The
// delay would make a light body unstable (the pressure carries the reaction of the fluid it
// accelerates, its added mass m_a, one step late), so the loads are stabilized as a rigid
// body's are (collide/collider.cpp). The vertex forces split into their rigid part, the net
// force F and torque tau about the centre of mass spread over the nodes as a rigid motion
// (f_i = m_i (F / m + I^-1 tau x r_i), which strains nothing), and the rest, which has no net
// force or torque. With m the body's mass and k = m_a / m, the rigid part becomes
//     F' = (F + m_a (a_seen - g)) / (1 + k),   tau' = (tau + k I alpha_seen) / (1 + k),
// where a_seen and alpha_seen are the changes of the body's motion (rigidMotion) that the
// fluid's step saw (fluid/solids/solid_motion_history.h), with m_a a_seen summed over the
// fluids and limited to the reaction the dynamic part shows (collide/solid_motion.h,
// shownReaction); the rest is scaled by 1 / (1 + k) too.
// In a viscous fluid the load also holds the viscous traction, a drag
// (fluid/solids/viscous_traction.h): per node and axis a coefficient C that the body's
// implicit step solves with its new velocity v', and the force at rest, f0 - C v' in all. It
// carries no added-mass reaction and takes no part in the stabilization, which would scale it
// down.
#pragma once

#include <cstdint>
#include <memory>

#include "collide/face_coverage.h"
#include "collide/solid_motion.h"
#include "core/allocator.h"
#include "core/math_types.h"
#include "core/status.h"
#include "fluid/solids/surface_pressure_load.h"
#include "geometry/surface_mesh.h"

namespace vp {

class FluidImmersion {
 public:
  // `boundary`'s vertex v is node vertexNode[v]; x holds 3 coordinates per node.
  Status build(const SurfaceMesh& boundary, const Array<int32_t>& vertexNode, const Array<double>& x);

  // The surface at positions x and velocities v (3 per node); it moves (a new surfaceMoves)
  // only when one of its vertices did.
  std::shared_ptr<const PreparedCollider> surface(const Array<double>& x, const Array<double>& v);

  // The loads of the fluids on this body: cleared, then added one by one: the hydrostatic
  // vertex forces of each liquid at the body's positions now, and the dynamic ones of each
  // fluid's last completed step with the change of the body's motion that step saw and, in a
  // viscous fluid, its drag (a load whose vertex count is not this surface's, or whose drag is
  // of another count or has a negative coefficient, is ignored whole and returns false).
  void clearLoads();
  bool addHydrostaticLoad(const Array<Vec3>& vertexForces);
  bool addLoad(const Array<Vec3>& dynamicForces, double addedMass, const SolidAcceleration& seen,
               const VertexDrag& drag);
  bool loaded() const { return loaded_; }
  // The surface's vertices at node positions x, and its outward triangles.
  Array<Eigen::Vector3d> vertices(const Array<double>& x) const;
  const Array<Eigen::Vector3i>& triangles() const { return surface_->triangles; }

  // The loads as node forces under gravity g, added to `force` (3 per node). Nodes touching a
  // collider (touching[node] != 0) take no dynamic force: the fluid between two solids closer
  // than a cell is not resolved (its pressure there swings with the gap, and one step late it
  // launches the body), and the contact carries the load there. They take the hydrostatic
  // one, which has no such swing: without it a light body resting on the floor would stay
  // there, pressed down by the liquid on its top.
  void addNodeForces(const Array<double>& x, const Array<double>& mass, const Vec3& gravity,
                     const Array<uint8_t>& touching, Array<double>* force) const;
  // The viscous drag on the nodes not touching a collider (3 per node each): C added to `drag`,
  // the force at rest to `force`.
  void addNodeDrag(const Array<uint8_t>& touching, Array<double>* drag, Array<double>* force) const;

  // A body of nodes at x with velocities v and masses `mass` (3, 3 and 1 per node) as a rigid
  // body: its centre of mass's velocity and its angular momentum about it over its inertia.
  static SolidMotion rigidMotion(const Array<double>& x, const Array<double>& v, const Array<double>& mass);

 private:
  Array<int32_t> vertexNode_;
  std::shared_ptr<PreparedCollider> surface_;
  Array<Eigen::Vector3d> positions_, velocities_;  // scratch
  Array<Vec3> forces_, hydrostaticForces_;  // per vertex, summed over the loads
  VertexDrag drag_;                          // per vertex, summed over the loads; empty without any
  double addedMass_ = 0.0;
  // The sums over the loads of added mass times the linear and the angular accelerations seen.
  Vec3 reaction_ = Vec3::Zero(), spinReaction_ = Vec3::Zero();
  bool loaded_ = false;
};

}  // namespace vp
