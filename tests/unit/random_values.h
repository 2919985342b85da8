// Reproducible test inputs: n values uniform in [-1, 1) from a seeded Mersenne twister, drawn in
// double and rounded to T (so a float and a double vector of one seed hold the same values up
// to rounding).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace vp::testing_values {

template <class T>
std::vector<T> randomValues(int64_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<T> v(static_cast<size_t>(n));
  for (T& x : v) x = T(u(rng));
  return v;
}

}  // namespace vp::testing_values
