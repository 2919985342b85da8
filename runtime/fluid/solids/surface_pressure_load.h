// Pressure tractions of a fluid on a deforming closed surface (a deformable's boundary,
// collide/face_coverage.h's deforming surface), as forces on its vertices.
//
// f_v = -sum over the triangles T at v of  integral over T of  p(x) n phi_v(x) dA,
// with phi_v the triangle's linear hat function of v, n the outward normal, and p the
// pressure extended into the solid and the liquid's air (extended_pressure.h) read by
// trilinear interpolation of the cell values; p = 0 where the liquid's level set, also
// interpolated, says air. The integral is the midpoint rule on a uniform subdivision of each
// triangle into pieces of edge at most half a cell (kMaxSubdivision per edge at most): a
// linear pressure (hydrostatic) is integrated exactly away from the waterline, so a body at
// rest under the liquid gets its buoyancy rho g V; the waterline's kink costs a part of
// (piece size / body size).
//
// Why the surface form here, when rigid bodies take the pressure gradient over the faces they
// cover (pressure_forces.h): a deformable needs the load where it acts, on its surface, or the
// buoyancy would pull its inside up instead of pushing its bottom. The ghost values keep the
// waterline where the level set has it, which the cell-centre air pressure alone would move
// by up to half a cell.
#pragma once

#include "collide/face_coverage.h"
#include "core/allocator.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/solids/face_fraction_field.h"
#include "fluid/solids/pressure_forces.h"

namespace vp {

// The viscous traction on a deforming surface (viscous_traction.h), kept apart from the
// pressure's forces because it is a drag: per vertex and axis the drag coefficient C that the
// fluid faces coupled to it put up (N s/m), and the force at rest. A vertex moving at v takes
// atRest - C v, which at the velocity the fluid's step saw is what the step took from it; the
// body solves it with its new velocity, as backward Euler takes a drag.
struct VertexDrag {
  Array<Vec3> coefficient, atRest;  // one each per surface vertex, or none
  bool empty() const { return coefficient.empty(); }
};

struct SurfacePressureLoad {
  Array<Vec3> vertexForces;  // one per surface vertex (N)
  VertexDrag drag;           // sized as vertexForces by addViscousTraction, else empty
  // The total force; torque about the origin; and the added mass: the fluid's density times
  // the body's volume times the wetted share of its surface (the area below the liquid). The
  // total holds the viscous traction at the velocities the step saw too (what the fluid's step
  // exchanged with the body in all); the body takes it through `drag`, not from here.
  PressureLoad total;
};

constexpr int kMaxSubdivision = 8;

// `surface` must be a deforming surface (vertexVelocities set); liquidPhi null for smoke. The
// triangles are integrated in parallel; the result does not depend on the worker count. `less`:
// the hydrostatic pressure under its free surface (surfaceHydrostaticLoad) is taken off the
// solve's at each point, which gives the dynamic part that a fluid step hands on (the added
// mass stays the wetted one).
void surfacePressureLoad(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                         const CutCellPoisson& op, const double* pressure, const double* liquidPhi, double density,
                         const PreparedCollider& surface, SurfacePressureLoad* out, const LiquidWeight* less = nullptr);

// The part of those forces that is the liquid's weight (fluid/surface/hydrostatic_pressure.h),
// by the same rule, on a closed surface given by its vertices and outward triangles; zero for
// smoke (liquidPhi null). A body takes it anew at its own steps from the liquid's last level
// set (deform/fluid_immersion.h), and the fluid's step the rest of its load.
void surfaceHydrostaticLoad(TaskSystem& tasks, const MacGrid& grid, const double* liquidPhi, double density,
                            const Vec3& gravity, const Array<Eigen::Vector3d>& vertices,
                            const Array<Eigen::Vector3i>& triangles, Array<Vec3>* vertexForces);

}  // namespace vp
