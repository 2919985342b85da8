// The position update after a deformable's implicit solve, with the body's spin turned exactly.
//
// Backward Euler moves each node along a straight line, x' = x + h v'. A body spinning at w
// has velocities w x r about its centre of mass, and the straight lines carry its nodes out
// to |r| sqrt(1 + (w h)^2): the step stretches the body by about (w h)^2 / 2, which the
// linearized corotational stiffness cannot see (it takes rotations as free) and which comes
// back as elastic energy in the next step. At a frame's step it is small; a body stepping
// several frames at once (a budget's lowered rate, a liquid's pace) is stretched enough for
// its steps to blow up (docs/choices.md, "Position update"). So the step's rigid part (the
// velocities' momentum and angular momentum as a rigid body's V and w) moves the body
// rigidly, translation and the exact rotation Q, and only the rest, d_i, moves along straight
// lines; the velocities relative to the centre turn with the body:
//     x'_i = c + h V + Q r_i + h d_i,   v''_i = V + Q (v'_i - V),   d_i = v'_i - V - w x r_i,
// that is x + h v' plus the turn's part beyond the tangent, (Q - I) r_i - h w x r_i, of second
// order in w h and towards the spin's axis. A spin about the new inertia then gives the
// velocities back the angular momentum about the centre that v' has (turning them turned it,
// which only a spin along it leaves alone). The momentum and the angular momentum are then
// those of v', as with straight lines; a rigid motion (every d_i = 0) comes out exact; without
// spin (Q = I) it is x + h v'. The d_i's velocities turn too: left unturned against the turned
// arms, they make a first-order angular momentum that the correction would take out as spin.
// The turn is the implicit midpoint rule's, in sub-turns of at most kMaxSubTurn (the .cpp; a rotation
// taken about the step's starting spin makes a free body whose spin is not along a principal
// axis gain kinetic energy every step).
// Pinned and attached nodes must end where their constraint puts them, so a body with any
// takes the straight lines (they hold it: it cannot spin freely about its centre of mass). A
// node held by a contact (a velocity of zero or along the collider) moves by the turn's part
// beyond the tangent only, towards the spin's axis: a rolling body's contact node lifts off as
// a point on a rolling wheel does.
#pragma once

#include "core/allocator.h"

namespace vp {

// x: positions at the step's start, moved in place; vSolved: the solve's velocities; v: out,
// the velocities at the new positions; mass: 1 per node.
void moveRotatingBody(const Array<double>& mass, double h, const Array<double>& vSolved, Array<double>* x,
                      Array<double>* v);

// x += h v' and v = v', the straight lines.
void moveAlongStraightLines(double h, const Array<double>& vSolved, Array<double>* x, Array<double>* v);

}  // namespace vp
