// A cantilever clamped at x = 0 under self-weight, solved to static equilibrium, and its
// analytic tip deflection (Euler–Bernoulli bending plus Timoshenko shear). Shared by the
// validation tests of linear and higher-order elements. The load is consistent for every
// degree: gravity acts through the lumped BB masses, and each Bernstein function integrates to
// V / C(n+3, 3), which is what ∫ ρ g B_α gives.
#pragma once

#include <cmath>
#include <utility>

#include "deform/deformable_body.h"
#include "geometry/box_tet_mesh.h"

namespace vp {

struct Beam {
  double length = 8.0, width = 1.0, height = 1.0;
  double E = 1e10, nu = 0.3, rho = 1000.0, g = 9.81;

  // q L⁴/(8EI) + q L²/(2κGA), q = ρ g A, with Cowper's shear coefficient of a rectangular
  // section κ = 10(1 + ν)/(12 + 11ν) (0.850 at ν = 0.3, 0.857 at 0.49; the shear term is under
  // 2% of the total on this slender beam, so κ = 5/6 would move it by 0.05% at most).
  double analyticTipDeflection() const {
    const double A = width * height, I = width * height * height * height / 12.0;
    const double q = rho * g * A, G = E / (2.0 * (1.0 + nu)), kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    return q * length * length * length * length / (8.0 * E * I) + q * length * length / (2.0 * kappa * G * A);
  }
};

// The beam's box [0, L] x [−h/2, h/2] x [−w/2, w/2] on cellsX x cellsYZ x cellsYZ cubes.
inline TetMesh beamTetMesh(const Beam& beam, int cellsX, int cellsYZ) {
  return makeBoxTetMesh({cellsX, cellsYZ, cellsYZ}, Vec3(beam.length, beam.height, beam.width),
                        Vec3(0, -0.5 * beam.height, -0.5 * beam.width));
}

// The beam's material on `mesh`, undamped, with linear solves run to 1e-9.
inline DeformableDesc beamDeformableDesc(const Beam& beam, int degree, TetMesh mesh) {
  DeformableDesc desc;
  desc.degree = degree;
  desc.mesh = std::move(mesh);
  desc.material.youngsModulus = beam.E;
  desc.material.poissonRatio = beam.nu;
  desc.material.density = beam.rho;
  desc.material.stiffnessDamping = 0.0;
  desc.solver.tolerance = 1e-9;
  desc.solver.maxIterations = 20000;
  return desc;
}

// Backward Euler with a 1 s step on this stiff beam is a Newton step of the static problem
// (h²K dominates M by ~1e8), so a few steps converge to equilibrium. Returns the mean
// downward displacement of the free end's nodes (for BB elements within 1e-5 of the area
// average of the field over the end face); cgIterations (may be null) sums the solves.
// mesh: the beam's box, beamTetMesh or another tetrahedralization of it.
inline double staticTipDeflection(const Beam& beam, int degree, TetMesh mesh, int* cgIterations) {
  std::unique_ptr<DeformableBody> body;
  if (!ok(DeformableBody::create(beamDeformableDesc(beam, degree, std::move(mesh)), &body))) return NAN;
  std::vector<int32_t> clamped, tip;
  for (int32_t i = 0; i < body->nodeCount(); ++i) {
    const double x = body->restPositions()[3 * i];
    if (x == 0.0) clamped.push_back(i);
    if (std::abs(x - beam.length) < 1e-9) tip.push_back(i);
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
  if (cgIterations) *cgIterations = 0;
  for (int step = 0; step < 10; ++step) {
    ActorStats stats;
    body->step(in, &stats);
    if (cgIterations) *cgIterations += stats.phase(Phase::Solve).iterations;
    current = tipDeflection();
    if (step > 0 && std::abs(current - previous) < 1e-6 * current) break;
    previous = current;
  }
  return current;
}

inline double staticTipDeflection(const Beam& beam, int degree, int cellsX, int cellsYZ, int* cgIterations) {
  return staticTipDeflection(beam, degree, beamTetMesh(beam, cellsX, cellsYZ), cgIterations);
}

}  // namespace vp
