// Small dense math types used across the runtime (Eigen, double precision unless a module
// states otherwise for its bulk storage).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vp {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

struct Pose {
  Vec3 position = Vec3::Zero();
  Quat rotation = Quat::Identity();

  Vec3 apply(const Vec3& local) const { return rotation * local + position; }
};

inline bool allFinite(const Vec3& v) { return v.allFinite(); }

}  // namespace vp
