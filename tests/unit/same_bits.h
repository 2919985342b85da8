// Bit-for-bit comparison of two vectors for tests that hold a CPU loop equal to a kernel body:
// reports the first index whose bits differ, with both values.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace vp::testing_values {

template <class T>
void expectSameBits(const std::vector<T>& expected, const std::vector<T>& actual, const char* what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  for (size_t i = 0; i < expected.size(); ++i)
    ASSERT_EQ(std::memcmp(&expected[i], &actual[i], sizeof(T)), 0)
        << what << " at " << i << ": " << expected[i] << " vs " << actual[i];
}

}  // namespace vp::testing_values
