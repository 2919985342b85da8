// Conformity of a tet mesh for the tests: every face shared by at most two tets, which see it
// with opposite orientations.
#pragma once

#include "geometry/tet_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace vp {
namespace test {

struct FaceUse {
  int count = 0;
  std::array<int32_t, 3> first{};
};

// The faces used by one tet only, after checking conformity: no face is used by more than two
// tets, and two tets that share a face see it with opposite orientations.
inline std::vector<std::array<int32_t, 3>> boundaryFaces(const TetMesh& mesh) {
  std::map<std::array<int32_t, 3>, FaceUse> faces;
  for (const auto& tet : mesh.tets)
    for (const auto& f : kTetFaces) {
      const std::array<int32_t, 3> oriented{{tet[f[0]], tet[f[1]], tet[f[2]]}};
      std::array<int32_t, 3> key = oriented;
      std::sort(key.begin(), key.end());
      FaceUse& use = faces[key];
      if (use.count == 1) {
        bool same = false;
        for (int r = 0; r < 3; ++r)
          same = same || (oriented[0] == use.first[r] && oriented[1] == use.first[(r + 1) % 3] &&
                          oriented[2] == use.first[(r + 2) % 3]);
        EXPECT_FALSE(same) << "a face shared by two tets with the same orientation";
      }
      if (use.count == 0) use.first = oriented;
      ++use.count;
    }
  std::vector<std::array<int32_t, 3>> boundary;
  for (const auto& [key, use] : faces) {
    EXPECT_LE(use.count, 2) << "a face shared by more than two tets";
    if (use.count == 1) boundary.push_back(use.first);
  }
  return boundary;
}

}  // namespace test
}  // namespace vp
