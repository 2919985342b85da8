// Extrapolation of the liquid velocity into the air (and optionally into closed faces), so that
// advection and interpolation near the surface read liquid-like velocities instead of stale
// air values.
//
// A face is known when it is not a domain Wall face, is open (effectiveOpenFraction > 0) and
// borders at least one liquid cell (phi < 0, free_surface.h): after a free-surface projection
// exactly these faces carry a projected velocity (slivers below minSourceOpenFraction excepted). Every other non-Wall face is a target (closed
// faces only when intoClosedFaces). Breadth-first layers over the face grid of each axis
// (the breadth-first extrapolation of Bridson, "Fluid Simulation for Computer Graphics"):
// layer L gives each target face that has a same-axis neighbour (+-x, +-y, +-z)
// of a layer < L the mean of those neighbours. Wall faces keep 0 and are no source (their
// value is the wall's, not the liquid's).
//
// Accuracy: each layer copies values one face further out, which is constant extrapolation
// along the grid directions towards the surface: a field that does not change along those
// directions (e.g. varies only tangentially to a flat surface) is reproduced exactly; a linear
// field u = a + g.x is off by at most L h max_i |g_i| on layer L (each layer's mean is over
// points one face back, each of which is within the previous bound). Constant rather than
// linear extrapolation on purpose: it cannot overshoot (values stay within the known range),
// which linear extrapolation over several layers would amplify.
//
// Parallel and deterministic: within a layer every target reads only faces of earlier layers
// and writes only itself (its mark, set once its part of the layer has its values, is the
// layer's own number, which no face of the layer takes as a source).
#pragma once

#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

struct VelocityExtrapolationSettings {
  int layers = 4;                // at least the advection's CFL number + 1
  bool intoClosedFaces = false;  // true: closed faces next to the liquid get liquid velocities too
  // Open liquid faces less open than this are targets, not known: a sliver's projected
  // velocity is barely constrained by the solve (fluid_actor.cpp).
  double minSourceOpenFraction = 0.0;
  // true: targets beyond the layers get velocity 0 (air faces out of the liquid's reach are
  // never projected; left alone they would gather gravity step after step).
  bool zeroUnreached = false;
};

// Per face after a call: 0 known, 1 .. layers the layer that set it, kExtrapolationUnreached
// for targets beyond the layers, kExtrapolationFixed for faces that are neither (Wall faces,
// closed faces unless intoClosedFaces).
// 253 is reserved too: within a call, a face claimed by a layer after the first until its value
// is set.
constexpr uint8_t kExtrapolationUnreached = 255;
constexpr uint8_t kExtrapolationFixed = 254;

struct VelocityExtrapolationState {
  Array<uint8_t> mark[3];
};

// liquidPhi: cellCount values (free_surface.h). layers in [0, 250]. Runs
// VelocityExtrapolationRun in one slice.
Status extrapolateVelocity(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions,
                           const double* liquidPhi, const VelocityExtrapolationSettings& settings,
                           VelocityExtrapolationState& state);

// extrapolateVelocity in slices, bitwise the same result however it is sliced and on any
// number of workers. Every pass (the marks, each layer of each axis, the zeroing) computes a
// face from values no other face of the pass writes, so a pass is cut into slabs. A slice does
// at most samplesPerSlice faces (one slab at least) and runs on into the next pass when one
// ends, so slices cost about the same throughout. A face set by layer L is marked L, which the
// rest of the layer does not take as a source (it takes marks < L), however the layer is cut.
// The marks, layer 1 and the zeroing scan the face rows, in slabs of consecutive rows (layer 1
// marks each slab's faces after its scan). Every later layer only visits the faces next to
// the layer before it (a face that layer L sets has all its sources in layer L - 1, else an
// earlier layer would have set it): it claims them in slabs of the last layer's list, fills
// them in slabs of the claimed list, in the same neighbour order as a scan, and marks them
// after the axis' last slab. Its cost follows the surface, not the grid.
// prepare() checks the arguments and sizes the marks but reads no values, so it may run before
// earlier work on the velocities. Between prepare() and the last slice, grid.velocity and the
// marks belong to the run, and the fractions and liquidPhi must stay as they are. A run kept
// from step to step reuses its storage.
class VelocityExtrapolationRun {
 public:
  Status prepare(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions, const double* liquidPhi,
                 const VelocityExtrapolationSettings& settings, VelocityExtrapolationState& state,
                 int64_t samplesPerSlice);
  // Runs one slice; true once all is done (also after a failed or missing prepare()).
  bool advance();
  bool done() const { return pass_ == Pass::Done; }
  int64_t lastSliceSamples() const { return lastSliceSamples_; }

 private:
  enum class Pass : uint8_t { Mark, Layer, Zero, Done };
  void markRows(int64_t begin, int64_t end);
  void extrapolateRows(int64_t begin, int64_t end);
  // Layers after the first, on the running axis: the faces next to entries [begin, end) of
  // its last layer, then entries [begin, end) of those, then their marks.
  void claimFrontier(int64_t begin, int64_t end);
  void extrapolateFrontier(int64_t begin, int64_t end);
  void finishFrontier();
  void zeroRows(int64_t begin, int64_t end);
  void nextAxis();

  TaskSystem* tasks_ = nullptr;
  MacGrid* grid_ = nullptr;
  const FaceFractionField* fractions_ = nullptr;
  const double* liquidPhi_ = nullptr;
  VelocityExtrapolationSettings settings_;
  VelocityExtrapolationState* state_ = nullptr;
  int64_t samplesPerSlice_ = 1, lastSliceSamples_ = 0;
  Pass pass_ = Pass::Done;
  int axis_ = 0, layer_ = 0;
  int64_t row_ = 0;  // next face row of the axis (j + dims.y * k), or entry of claimed_
  int64_t layerFaces_ = 0;  // faces the running layer has set
  std::vector<Array<int64_t>> assigned_;  // per chunk of a slab: the faces it set
  Array<int64_t> lastLayer_[3];            // per axis: the faces its last layer set
  Array<int64_t> claimed_;                 // the running layer's faces (after layer 1)
  bool claimedAxis_ = false;                     // claimed_ holds all the running axis' faces
};

}  // namespace vp
