// Cantilever under self-weight, linear corotational tets vs Euler–Bernoulli beam theory with
// Timoshenko's shear correction, on three refinements (the validation table).
#include <gtest/gtest.h>

#include <cstdio>

#include "deform/deformable_body.h"
#include "geometry/box_tet_mesh.h"

namespace vp {
namespace {

struct Beam {
  double length = 8.0, width = 1.0, height = 1.0;
  double E = 1e10, nu = 0.3, rho = 1000.0, g = 9.81;

  // Tip deflection under the uniform load q = ρ g A: bending qL⁴/(8EI) plus shear
  // qL²/(2κGA) with κ = 5/6 for a rectangular section.
  double analyticTipDeflection() const {
    const double A = width * height, I = width * height * height * height / 12.0;
    const double q = rho * g * A, G = E / (2.0 * (1.0 + nu)), kappa = 5.0 / 6.0;
    return q * length * length * length * length / (8.0 * E * I) + q * length * length / (2.0 * kappa * G * A);
  }
};

// Static deflection: backward Euler with a 1 s step on this stiff beam is a Newton step of
// the static problem (h²K dominates M by ~1e8), so a few steps converge to equilibrium.
double simulatedTipDeflection(const Beam& beam, int cellsX, int cellsYZ, int* cgIterations) {
  DeformableDesc desc;
  desc.mesh = makeBoxTetMesh({cellsX, cellsYZ, cellsYZ}, Vec3(beam.length, beam.height, beam.width),
                             Vec3(0, -0.5 * beam.height, -0.5 * beam.width));
  desc.material.youngsModulus = beam.E;
  desc.material.poissonRatio = beam.nu;
  desc.material.density = beam.rho;
  desc.material.stiffnessDamping = 0.0;
  desc.solver.tolerance = 1e-9;
  desc.solver.maxIterations = 20000;
  std::unique_ptr<DeformableBody> body;
  EXPECT_EQ(DeformableBody::create(desc, &body), Status::Ok) << lastError();
  std::vector<int32_t> clamped, tip;
  for (int32_t i = 0; i < body->nodeCount(); ++i) {
    const double x = body->restPositions()[3 * i];
    if (x == 0.0) clamped.push_back(i);
    if (std::abs(x - beam.length) < 1e-12) tip.push_back(i);
  }
  body->setPinned(clamped.data(), static_cast<int64_t>(clamped.size()), true);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.dt = 1.0;
  in.tasks = tasks.get();
  in.gravity = Vec3(0, -beam.g, 0);
  auto tipDeflection = [&] {
    double sum = 0.0;
    for (int32_t i : tip) sum += body->restPositions()[3 * i + 1] - body->positions()[3 * i + 1];
    return sum / static_cast<double>(tip.size());
  };
  double previous = 0.0, current = 0.0;
  *cgIterations = 0;
  for (int step = 0; step < 10; ++step) {
    ActorStats stats;
    body->step(in, &stats);
    *cgIterations += stats.phase(Phase::Solve).iterations;
    current = tipDeflection();
    if (step > 0 && std::abs(current - previous) < 1e-6 * current) break;
    previous = current;
  }
  return current;
}

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
    const double tip = simulatedTipDeflection(beam, cx, cyz, &iterations);
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
