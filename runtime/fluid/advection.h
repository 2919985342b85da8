// Transport of MAC velocities and cell-centred scalars by the grid's velocity field.
//
// Semi-Lagrangian: each sample point (face or cell centre) is traced back through the
// velocity with the midpoint rule (RK2: x_mid = x - dt/2 u(x), x_back = x - dt u(x_mid)) and
// the old field is interpolated trilinearly there. Unconditionally stable, first order in
// space, and dissipative: it smooths every step.
//
// MacCormack (Selle, Fedkiw, Kim, Liu, Osher 2008): a forward semi-Lagrangian step phi^,
// a backward one from phi^ (tracing forward in time) phi~, and the corrected
// phi^ + (phi - phi~) / 2, which cancels the leading error term. A scalar is clamped to the
// range of the 8 old samples that the forward step interpolated, so the correction never
// creates new extrema (the scheme stays stable); a velocity outside that range keeps the
// semi-Lagrangian phi^ instead (clamping it fed energy into a stirred liquid, advection.cpp).
// Twice the cost, much less dissipation.
//
// Points traced out of the domain take the boundary's values (clamped sampling).
//
// Cell-centred scalars can be sampled through the open faces only (CellOpenFaces): a sample
// then uses, of its 8 cells, those connected to the fluid cell nearest the sample point by
// open faces inside the 2 x 2 x 2 block (connectedTrilinearSample in grid_sampling.h), and
// cells with no open face take a fixed solid value instead of being advected. Plain
// trilinear stencils reach across a collider one cell thick (two cells diagonal to each
// other can lie on its two sides), so smoke would be interpolated through it. Blocks away
// from colliders have every inner face open and cost one flag test more.
#pragma once

#include <cstdint>
#include <vector>

#include "core/task_system.h"
#include "fluid/face_fraction_field.h"
#include "fluid/fluid_desc.h"
#include "fluid/mac_grid.h"

namespace vp {

// Scratch arrays, kept between steps so advection does not allocate.
struct AdvectionWorkspace {
  std::vector<double> advected[3];  // new velocity, per axis
  std::vector<double> forward, rangeLo, rangeHi;
  std::vector<Eigen::Vector3d> cellTrace;  // per cell: where its centre came from
  std::vector<uint8_t> kept;               // per cell: left as it was (keepBeyond)
};

// Per-cell open faces for advection that does not interpolate across solids (layout in
// grid_sampling.h: faces bits and kCellIsFluid, blockOpen flags).
struct CellOpenFaces {
  std::vector<uint8_t> faces;
  std::vector<uint8_t> blockOpen;
};

// From the effective open fractions (cut_cell_poisson.h: Wall faces and slivers closed).
void buildCellOpenFaces(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions, CellOpenFaces* out);

// Faces that nothing downstream reads can be left out of advection: face f normal to axis a
// with marks[a][f] == skipMark keeps its value. A liquid passes its velocity extrapolation's
// marks: air faces beyond the extrapolated layers are zeroed after every projection and lie
// farther from the liquid than a sub-step's trace reaches (a third of the tank's faces in the
// default scene).
struct FaceSkipMask {
  const std::vector<uint8_t>* marks = nullptr;  // 3 arrays, one per axis; null: advect all
  uint8_t skipMark = 0;
};

// Replaces grid.velocity by itself advected over dt.
void advectVelocity(TaskSystem& tasks, MacGrid& grid, double dt, AdvectionScheme scheme, AdvectionWorkspace& work,
                    const FaceSkipMask& skip = {});

// Advects cell-centred scalars (each cellCount() values, cell order) by grid.velocity over dt.
// All fields share the traced points, so pass them together.
// openFaces (optional): sample through open faces only; cells with no open face are then set
// to solidValues[field] (or keep their value when solidValues is null).
// keepBeyond (optional, > 0): cells where |first field| >= keepBeyond keep their values. For a
// level set that is redistanced after advection, cells farther from the surface than the
// step can move it (plus the interpolation stencil) keep their sign, and redistancing
// rewrites their magnitude anyway.
void advectCellScalars(TaskSystem& tasks, const MacGrid& grid, double dt, AdvectionScheme scheme,
                       std::vector<double>* const* fields, int fieldCount, AdvectionWorkspace& work,
                       const CellOpenFaces* openFaces = nullptr, const double* solidValues = nullptr,
                       double keepBeyond = 0.0);

}  // namespace vp
