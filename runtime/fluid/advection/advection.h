// Transport of MAC velocities and cell-centred scalars by the grid's velocity field.
//
// Semi-Lagrangian: each sample point (face or cell centre) is traced back through the
// velocity with the midpoint rule (RK2: x_mid = x - dt/2 u(x), x_back = x - dt u(x_mid)) and
// the old field is interpolated trilinearly there. Unconditionally stable, first order in
// space, and dissipative: it smooths every step.
//
// MacCormack (Selle, Fedkiw, Kim, Liu, Osher 2008): a forward semi-Lagrangian step phi^,
// a backward one from phi^ phi~, and the corrected phi^ + (phi - phi~) / 2, which cancels the
// leading error term. The backward step samples phi^ at each point's back-trace reflected
// through the point (kernels::reflectThrough), kept from the forward step, instead of tracing
// forward in time through the velocity again: the two differ by dt^2 (u . grad) u, the order
// of the midpoint rule's own error, and the reflection costs no velocity samples. A scalar is
// clamped to the range of the 8 old samples that the forward step interpolated, so the
// correction never creates new extrema (the scheme stays stable); a velocity outside that
// range keeps the semi-Lagrangian phi^ instead (clamping it fed energy into a stirred liquid,
// advection.cpp). One more sampling pass than semi-Lagrangian, much less dissipation.
//
// Points traced out of the domain take the boundary's values (clamped sampling), but for a
// liquid's level set beyond an Open side: what lies there is air (the side's p = 0 is the
// atmosphere's), so such a point takes at least its distance beyond the side. Clamped, a
// liquid cell on an open side would draw liquid from outside as long as the flow enters
// there: a sheet at an open top falls forever, fed from above.
//
// Sliced (VelocityAdvectionSlices, ScalarAdvectionSlices): every pass computes each sample
// from the pass's inputs alone, so a pass's rows can be cut into slabs run one at a time,
// with frames in between, and give bitwise what one call gives. advectVelocity and
// advectCellScalars are the same passes run as one slab each.
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

#include "core/allocator.h"
#include "core/slab_passes.h"
#include "core/task_system.h"
#include "fluid/fluid_desc.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

struct TraceStarts;  // advection_rows.h

// Scratch arrays, kept between steps so advection does not allocate.
struct AdvectionWorkspace {
  Array<double> advected[3];  // new velocity, per axis
  Array<double> forward, rangeLo, rangeHi;
  // Back-traces kept from a forward pass: per cell for scalars (shared by every field), or per
  // face of the axis being advected for velocity MacCormack's correction (traceEntries in
  // advection.cpp: sized once for both).
  Array<Eigen::Vector3d> traces;
  Array<uint8_t> kept;               // per cell: left as it was (keepBeyond)
};

// Per-cell open faces for advection that does not interpolate across solids (layout in
// grid_sampling.h: faces bits and kCellIsFluid, blockOpen flags).
struct CellOpenFaces {
  Array<uint8_t> faces;
  Array<uint8_t> blockOpen;
};

// From the effective open fractions (cut_cell_poisson.h: Wall faces and slivers closed).
void buildCellOpenFaces(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions, CellOpenFaces* out);

// Faces that nothing downstream reads can be left out of advection: face f normal to axis a
// with marks[a][f] == skipMark keeps its value. A liquid passes its velocity extrapolation's
// marks: air faces beyond the extrapolated layers are zeroed after every projection and lie
// farther from the liquid than a sub-step's trace reaches (a third of the tank's faces in the
// default scene).
struct FaceSkipMask {
  const Array<uint8_t>* marks = nullptr;  // 3 arrays, one per axis; null: advect all
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
// conservedField (optional, >= 0): that field's total is kept (a smoke density): after
// advection it is scaled so that its sum is the old sum less what the outward velocities of
// the open domain sides carried out of their boundary cells over dt. What flows in through an
// open side brings none (a conserved field's ambient value is 0). Neither scheme conserves
// on its own: trilinear back-traces gain where the interpolated velocity converges (a
// plume's base), and MacCormack's clamp to the stencil's range adds more, so a hot plume
// held far more smoke than it was given. A uniform scale is the correction that keeps the
// field's shape and sign (as the liquid's volume correction is a uniform shift).
// levelSetField (optional, >= 0): that field is a liquid level set (free_surface.h) with air
// beyond the Open sides (see the top of this header), and its sheets thinner than a cell close
// at the rate their faces' inflow closes them (kernels::sheetClosingSpeed), which a trace from
// the cell centre cannot see.
void advectCellScalars(TaskSystem& tasks, const MacGrid& grid, double dt, AdvectionScheme scheme,
                       Array<double>* const* fields, int fieldCount, AdvectionWorkspace& work,
                       const CellOpenFaces* openFaces = nullptr, const double* solidValues = nullptr,
                       double keepBeyond = 0.0, int conservedField = -1, int levelSetField = -1);

// Rows [rowBegin, rowEnd) (x-lines, numbered j + dims.y * k) of one pass's sample lattice:
// the unit a slice of advection runs (core/slab_passes.h cuts the passes into slices).
struct AdvectionRows {
  int target;  // the axis or field the pass works on
  Eigen::Vector3i dims;  // of the pass's lattice
  int64_t rowBegin, rowEnd;
};

// One sub-step's velocity advection (advectVelocity) as a sequence of slices: for each axis,
// for each pass (semi-Lagrangian: one; MacCormack: forward, keeping each face's back-trace,
// then correction), that axis's face rows, as SlabPasses (core/slab_passes.h) that a slice
// runs up to a bound on samples, decided per slice (one row at least). The slices write the
// workspace only, so grid.velocity stays the old field that every trace samples until
// finish() swaps the advected one in.
//
// Between prepare() and finish() the grid, the workspace and the skip marks must outlive this
// object and be left alone by everything else; the object stays where it is (its passes
// point at it).
class VelocityAdvectionSlices {
 public:
  VelocityAdvectionSlices() = default;
  VelocityAdvectionSlices(const VelocityAdvectionSlices&) = delete;
  VelocityAdvectionSlices& operator=(const VelocityAdvectionSlices&) = delete;

  // Sizes the workspace and lists the passes, which run on `tasks`.
  void prepare(TaskSystem& tasks, MacGrid& grid, double dt, AdvectionScheme scheme, AdvectionWorkspace& work,
               const FaceSkipMask& skip);
  // Runs the next slice of at most maxSamples face samples (one row at least), parallel over
  // its rows; true when every pass is done.
  bool runSlice(int64_t maxSamples, const Deadline* stop = nullptr) { return passes_.runSlice(maxSamples, stop); }
  int64_t lastSliceSamples() const { return passes_.lastSliceSamples(); }
  // After the last slice: grid.velocity becomes the advected velocity.
  void finish();

 private:
  void forwardPass(const AdvectionRows& rows);
  void correctionPass(const AdvectionRows& rows);

  MacGrid* grid_ = nullptr;
  AdvectionWorkspace* work_ = nullptr;
  double dt_ = 0.0;
  bool maccormack_ = false;
  FaceSkipMask skip_;
  SlabPasses passes_;
};

// advectCellScalars as a sequence of slices: the trace pass shared by all fields, then per
// field its passes (semi-Lagrangian: one; MacCormack: forward, then correction), as
// SlabPasses that a slice runs up to a bound on cells (one row at least). Right after a
// field's last pass the field is swapped with its advected values, as advectCellScalars does,
// so after the last slice every field is advected and nothing is left to finish.
//
// Between prepare() and the last slice the grid, the fields, the workspace and openFaces must
// outlive this object and be left alone by everything else; the list of field pointers and
// solidValues are copied. The object stays where it is (its passes point at it).
class ScalarAdvectionSlices {
 public:
  ScalarAdvectionSlices() = default;
  ScalarAdvectionSlices(const ScalarAdvectionSlices&) = delete;
  ScalarAdvectionSlices& operator=(const ScalarAdvectionSlices&) = delete;

  // Arguments as advectCellScalars'. Sizes the workspace and lists the passes, which run on
  // `tasks` (none when fieldCount <= 0).
  void prepare(TaskSystem& tasks, const MacGrid& grid, double dt, AdvectionScheme scheme,
               Array<double>* const* fields, int fieldCount, AdvectionWorkspace& work,
               const CellOpenFaces* openFaces, const double* solidValues, double keepBeyond,
               int conservedField = -1, int levelSetField = -1);
  // Runs the next slice of at most maxSamples cell samples (one row at least), parallel over
  // its rows; true when every pass is done.
  bool runSlice(int64_t maxSamples, const Deadline* stop = nullptr) { return passes_.runSlice(maxSamples, stop); }
  int64_t lastSliceSamples() const { return passes_.lastSliceSamples(); }

 private:
  void tracePass(const AdvectionRows& rows);
  void forwardPass(const AdvectionRows& rows);
  void correctionPass(const AdvectionRows& rows);
  // The level set's values at the batch's traced points raised to at least their distance
  // beyond the Open sides, and rangeHigh (MacCormack's clamp range; may be null) with them (a
  // no-op for other fields and for traces inside the domain).
  void keepAirBeyondOpenSides(const AdvectionRows& rows, const TraceStarts& cells, const Eigen::Vector3d* traces,
                              double* values, double* rangeHigh) const;
  // The conserved field's total: row sums in parallel, added in row order (the same on any
  // number of workers). Before advection: the target (the total less the open sides'
  // outflow); after: the scale that meets it, applied.
  void addRowSumPass(int field);
  double rowSumTotal() const;
  void addTargetTotalPasses(int field);
  void addRescalePasses(int field);
  // The level set's sheets thinner than a cell closed (kernels::sheetClosingSpeed) after its
  // advection: each cell's rise over dt into work.forward (free once the field's own passes
  // are done), then added, so no cell reads another's new value.
  void addSheetClosingPasses(int field);

  const MacGrid* grid_ = nullptr;
  AdvectionWorkspace* work_ = nullptr;
  double dt_ = 0.0;
  bool maccormack_ = false;
  std::vector<Array<double>*> fields_;
  const CellOpenFaces* openFaces_ = nullptr;
  Array<double> solidValues_;  // per field; empty: solid cells keep their values
  double keepBeyond_ = 0.0;
  int levelSetField_ = -1;
  Array<double> rowSums_;
  double targetTotal_ = 0.0, scale_ = 1.0;
  SlabPasses passes_;
};

}  // namespace vp
