#include "core/physical_limits.h"

#include <cmath>
#include <cstdio>

namespace vp {
namespace {

// A host's float quaternion may be off unit length by round-off; further off is a host bug.
constexpr double kUnitQuaternionTolerance = 1e-2;

Status checkMagnitude(const char* field, const Vec3& v, double limit, const char* unit) {
  if (!v.allFinite() || v.norm() > limit)
    return fail(Status::InvalidArgument, "%s = (%g, %g, %g): must be finite with magnitude <= %g %s", field, v.x(),
                v.y(), v.z(), limit, unit);
  return Status::Ok;
}

}  // namespace

Status checkPosition(const char* field, const Vec3& p) {
  if (!p.allFinite() || p.cwiseAbs().maxCoeff() > kMaxCoordinate)
    return fail(Status::InvalidArgument, "%s = (%g, %g, %g): coordinates must be finite and within +-%g m", field,
                p.x(), p.y(), p.z(), kMaxCoordinate);
  return Status::Ok;
}

Status checkPose(const char* field, Pose* pose) {
  char sub[96];
  std::snprintf(sub, sizeof sub, "%s.position", field);
  VP_TRY(checkPosition(sub, pose->position));
  const Quat& q = pose->rotation;
  const double n = q.norm();
  if (!std::isfinite(n) || std::abs(n - 1.0) > kUnitQuaternionTolerance)
    return fail(Status::InvalidArgument, "%s.rotation = (%g, %g, %g, %g): must be a unit quaternion (norm %g)", field,
                q.x(), q.y(), q.z(), q.w(), n);
  pose->rotation.normalize();
  return Status::Ok;
}

Status checkLength(const char* field, double value) {
  if (!(value >= kMinLength && value <= kMaxLength))  // also NaN
    return fail(Status::InvalidArgument, "%s = %g: must be in [%g, %g] m", field, value, kMinLength, kMaxLength);
  return Status::Ok;
}

Status checkMass(const char* field, double value) {
  if (!(value >= kMinMass && value <= kMaxMass))
    return fail(Status::InvalidArgument, "%s = %g: must be in [%g, %g] kg", field, value, kMinMass, kMaxMass);
  return Status::Ok;
}

Status checkDensity(const char* field, double value) {
  if (!(value >= kMinDensity && value <= kMaxDensity))
    return fail(Status::InvalidArgument, "%s = %g: must be in [%g, %g] kg/m^3", field, value, kMinDensity, kMaxDensity);
  return Status::Ok;
}

Status checkLinearVelocity(const char* field, const Vec3& v) { return checkMagnitude(field, v, kMaxSpeed, "m/s"); }

Status checkAngularVelocity(const char* field, const Vec3& v) {
  return checkMagnitude(field, v, kMaxAngularSpeed, "rad/s");
}

Status checkLoad(const char* field, const Vec3& load) { return checkMagnitude(field, load, kMaxLoad, "(SI units)"); }

}  // namespace vp
