// Reproducible test inputs: n values uniform in [-1, 1) from a seeded Mersenne twister, drawn in
// double and rounded to T (so a float and a double vector of one seed hold the same values up
// to rounding); a vector and a unit quaternion of draws in a fixed order.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vp::testing_values {

template <class T>
std::vector<T> randomValues(int64_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<T> v(static_cast<size_t>(n));
  for (T& x : v) x = T(u(rng));
  return v;
}

// x, then y, then z. Drawn as a call's arguments (Vec3(u(rng), u(rng), u(rng))) they come in the
// order the compiler evaluates arguments in, so the test's cases would depend on the compiler.
template <class Distribution, class Engine>
Eigen::Vector3d randomVector(Distribution& u, Engine& rng) {
  const double x = u(rng), y = u(rng), z = u(rng);
  return Eigen::Vector3d(x, y, z);
}

// w, x, y, z, normalized (a uniform rotation from a normal distribution).
template <class Distribution, class Engine>
Eigen::Quaterniond randomQuaternion(Distribution& g, Engine& rng) {
  const double w = g(rng), x = g(rng), y = g(rng), z = g(rng);
  return Eigen::Quaterniond(w, x, y, z).normalized();
}

}  // namespace vp::testing_values
