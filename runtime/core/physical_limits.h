// The range of quantities VolPhys simulates, checked where a value enters (a def, a setter, a
// scene file) and nowhere else. A value outside is a unit mistake or garbage: a denormal mass
// whose inverse overflows Bullet's floats, a body placed at 1e30 m whose grid index overflows
// an int, a 1e308 from a JSON file that becomes +inf in a float pose. Each check names the
// field and its value.
#pragma once

#include "core/math_types.h"
#include "core/status.h"

namespace vp {

// Largest |coordinate| of a position: beyond it a float position resolves less than a
// decimetre, and the host is better served by a floating origin.
constexpr double kMaxCoordinate = 1e6;
// Lengths (radii, half extents, cell sizes) between a micrometre and kMaxLength; sizes past it
// are almost certainly millimetres given as metres.
constexpr double kMinLength = 1e-6;
constexpr double kMaxLength = 1e5;
// Masses between a milligram and kMaxMass: below it Bullet's inverse mass and inertia lose
// their float range.
constexpr double kMinMass = 1e-6;
constexpr double kMaxMass = 1e9;
// Densities of the materials and fluids, from a thin gas to beyond any solid.
constexpr double kMinDensity = 1e-6;
constexpr double kMaxDensity = 1e6;
// Linear speeds up to kMaxSpeed m/s, angular up to kMaxAngularSpeed rad/s.
constexpr double kMaxSpeed = 1e5;
constexpr double kMaxAngularSpeed = 1e5;

// Forces, torques and impulses a host applies: up to what brings the heaviest body to the top
// speed in one second (or at once, for an impulse).
constexpr double kMaxLoad = kMaxMass * kMaxSpeed;

Status checkPosition(const char* field, const Vec3& position);
// Position in range, rotation a unit quaternion up to float round-off (then normalized).
Status checkPose(const char* field, Pose* pose);
Status checkLength(const char* field, double length);
Status checkMass(const char* field, double mass);
Status checkDensity(const char* field, double density);
Status checkLinearVelocity(const char* field, const Vec3& velocity);
Status checkAngularVelocity(const char* field, const Vec3& velocity);
// A force, torque or impulse (any of them): finite, at most kMaxLoad in magnitude.
Status checkLoad(const char* field, const Vec3& load);

}  // namespace vp
