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
// and writes only itself (its mark is set after the layer's scan).
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.h"
#include "core/task_system.h"
#include "fluid/face_fraction_field.h"
#include "fluid/mac_grid.h"

namespace vp {

struct VelocityExtrapolationSettings {
  int layers = 4;                // at least the advection's CFL number + 1
  bool intoClosedFaces = false;  // true: closed faces next to the liquid get liquid velocities too
  // Open liquid faces less open than this are targets, not known: a sliver's projected
  // velocity is barely constrained by the solve (fluid_actor.cpp).
  double minSourceOpenFraction = 0.0;
};

// Per face after a call: 0 known, 1 .. layers the layer that set it, kExtrapolationUnreached
// for targets beyond the layers, kExtrapolationFixed for faces that are neither (Wall faces,
// closed faces unless intoClosedFaces).
constexpr uint8_t kExtrapolationUnreached = 255;
constexpr uint8_t kExtrapolationFixed = 254;

struct VelocityExtrapolationState {
  std::vector<uint8_t> mark[3];
};

// liquidPhi: cellCount values (free_surface.h). layers in [0, 250].
Status extrapolateVelocity(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions,
                           const double* liquidPhi, const VelocityExtrapolationSettings& settings,
                           VelocityExtrapolationState& state);

}  // namespace vp
