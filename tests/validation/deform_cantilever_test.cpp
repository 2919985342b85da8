// Cantilever under self-weight, linear corotational tets vs Euler–Bernoulli beam theory with
// Timoshenko's shear correction, on three refinements (the validation table).
#include <gtest/gtest.h>

#include <cstdio>

#include "static_beam.h"

namespace vp {
namespace {

TEST(CantileverValidation, LinearTetsConvergeToBeamTheory) {
  Beam beam;
  const double analytic = beam.analyticTipDeflection();
  const int refinements[3][2] = {{24, 3}, {48, 6}, {96, 12}};
  double errors[3];
  std::printf("\n  cantilever L=%.0f m, %gx%g m section, E=%.0e Pa, nu=%.2f, self-weight\n", beam.length, beam.height,
              beam.width, beam.E, beam.nu);
  std::printf("  analytic tip deflection (Euler-Bernoulli + Timoshenko shear): %.6e m\n", analytic);
  std::printf("  %-12s %8s %14s %10s %10s\n", "cubes", "tets", "tip [m]", "error", "cg iters");
  for (int r = 0; r < 3; ++r) {
    int iterations = 0;
    const int cx = refinements[r][0], cyz = refinements[r][1];
    const double tip = staticTipDeflection(beam, 1, cx, cyz, &iterations);
    errors[r] = std::abs(tip - analytic) / analytic;
    std::printf("  %3dx%dx%-6d %8d %14.6e %9.2f%% %10d\n", cx, cyz, cyz, 6 * cx * cyz * cyz, tip, 100 * errors[r],
                iterations);
  }
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
  EXPECT_LT(errors[2], 0.05);
}

}  // namespace
}  // namespace vp
