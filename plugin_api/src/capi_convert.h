// Conversions between the C ABI's plain structs and runtime types, and the guard that turns
// runtime statuses and C++ exceptions into vpStatus at the boundary.
#pragma once

#include <cstring>
#include <exception>
#include <type_traits>
#include <new>

#include "core/collision_filter.h"
#include "core/math_types.h"
#include "core/status.h"
#include "volphys/volphys.h"

namespace vp::capi {

inline Vec3 toVec3(const vpVec3& v) { return Vec3(v.x, v.y, v.z); }
inline vpVec3 toC(const Vec3& v) { return vpVec3{float(v.x()), float(v.y()), float(v.z())}; }
inline Quat toQuat(const vpQuat& q) { return Quat(q.w, q.x, q.y, q.z); }
inline vpQuat toC(const Quat& q) { return vpQuat{float(q.x()), float(q.y()), float(q.z()), float(q.w())}; }
inline Pose toPose(const vpTransform& t) { return Pose{toVec3(t.position), toQuat(t.rotation)}; }
inline vpTransform toC(const Pose& p) { return vpTransform{toC(p.position), toC(p.rotation)}; }
inline CollisionFilter toFilter(const vpCollisionFilter& f) { return CollisionFilter{f.categoryBits, f.maskBits}; }
inline vpCollisionFilter toC(const CollisionFilter& f) { return vpCollisionFilter{f.category, f.mask}; }

static_assert(static_cast<int>(Status::PhaseFailed) == vpStatus_PhaseFailed, "vp::Status and vpStatus must match");
static_assert(static_cast<int>(Status::NotConverged) == vpStatus_NotConverged, "vp::Status and vpStatus must match");
inline vpStatus toC(Status s) { return static_cast<vpStatus>(s); }

// A C enum field may hold any int the host wrote; in C++ loading an out-of-range value as the
// enum type is undefined, so enum fields are read through their bits.
template <class Enum>
int rawEnum(const Enum& field) {
  static_assert(sizeof(Enum) == sizeof(int), "C enums are int-sized here");
  int value;
  std::memcpy(&value, &field, sizeof value);
  return value;
}

// The C ABI function running on this thread (nullptr outside one); a Busy error names the
// call that holds the world.
inline thread_local const char* t_currentCall = nullptr;
inline const char* currentCall() { return t_currentCall; }

// Runs `body` (returning vp::Status); no exception crosses the C boundary.
template <class Body>
vpStatus guarded(const char* function, Body&& body) {
  struct CallScope {
    const char* outer = t_currentCall;
    explicit CallScope(const char* f) { t_currentCall = f; }
    ~CallScope() { t_currentCall = outer; }
  } scope(function);
  try {
    return toC(body());
  } catch (const std::bad_alloc&) {
    return toC(fail(Status::OutOfMemory, "%s: out of memory", function));
  } catch (const std::exception& e) {
    return toC(fail(Status::Internal, "%s: internal error: %s", function, e.what()));
  } catch (...) {
    return toC(fail(Status::Internal, "%s: internal error", function));
  }
}

// Null output pointers are host bugs; report them by parameter name.
#define VP_REQUIRE_POINTER(p) \
  if (!(p)) return ::vp::fail(::vp::Status::InvalidArgument, "%s: " #p " is NULL", __func__)


Status checkVec3(const char* field, const vpVec3& v);

}  // namespace vp::capi
