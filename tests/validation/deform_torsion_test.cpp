// Torsion of a square bar (St-Venant): clamped at x = 0, torque T about the bar's axis at
// x = L. Away from both ends the twist rate is θ' = T / (G J), J = β a⁴ with β = 0.1406 for a
// square of side a (the series solution, Timoshenko & Goodier §109), whatever the load's
// distribution over the end face.
//
// The torque enters as tangential nodal forces on the end face, f_i = T w_i (e_x × r_i) /
// Σ_j w_j |r_j|², with w_i = ∫ B_i dA the face's BB lumped weights and r_i the node's offset
// from the axis. Their resultant torque is exactly T and their resultant force exactly zero
// (Σ w_i r_i = ∫ r dA = 0 because BB reproduces linear fields), so they differ from St-Venant's
// shear distribution only by a self-equilibrated load, which by St-Venant's principle decays
// within about one side length of the end. The twist is measured between x = 1.5a and
// x = L − 1.5a, as the rotation about the axis that best fits the in-plane displacements of
// the nodes in each cross-section (warping is axial and does not enter).
#include <gtest/gtest.h>

#include <cstdio>

#include "deform/bb_multi_index.h"
#include "deform/deformable_body.h"
#include "geometry/box_tet_mesh.h"

namespace vp {
namespace {

struct TorsionBar {
  double side = 1.0, length = 6.0;
  double E = 1e10, nu = 0.3, torque = 1e5;
  double G() const { return E / (2.0 * (1.0 + nu)); }
  double J() const { return 0.1406 * side * side * side * side; }
};

// The measured twist between the two inner sections, and the analytic one.
struct TwistResult {
  double measured = NAN, analytic = NAN;
  int iterations = 0;
};

TwistResult twistOfBar(const TorsionBar& bar, int degree, int cellsAlong, int cellsAcross) {
  TwistResult result;
  DeformableDesc desc;
  desc.degree = degree;
  desc.mesh = makeBoxTetMesh({cellsAlong, cellsAcross, cellsAcross}, Vec3(bar.length, bar.side, bar.side),
                             Vec3(0, -0.5 * bar.side, -0.5 * bar.side));
  desc.material.youngsModulus = bar.E;
  desc.material.poissonRatio = bar.nu;
  desc.material.stiffnessDamping = 0.0;
  desc.solver.tolerance = 1e-10;
  desc.solver.maxIterations = 20000;
  const TetMesh mesh = desc.mesh;
  std::unique_ptr<DeformableBody> body;
  if (!ok(DeformableBody::create(desc, &body))) return result;
  const Array<double>& X = body->restPositions();
  std::vector<int32_t> clamped;
  for (int32_t i = 0; i < body->nodeCount(); ++i)
    if (X[3 * i] == 0.0) clamped.push_back(i);
  body->setPinned(clamped.data(), static_cast<int64_t>(clamped.size()), true);

  // Lumped weights of the end face's nodes: each of a triangle's C(n+2, 2) BB functions
  // integrates to area / C(n+2, 2).
  const int N = bbNodeCount(degree);
  const BBMultiIndex* alpha = bbMultiIndices(degree);
  std::vector<double> weight(static_cast<size_t>(body->nodeCount()), 0.0);
  auto atEnd = [&](int32_t node) { return std::abs(X[3 * node] - bar.length) < 1e-9; };
  for (size_t e = 0; e < mesh.tets.size(); ++e)
    for (int opposite = 0; opposite < 4; ++opposite) {
      int corners[3], c = 0;
      for (int v = 0; v < 4; ++v)
        if (v != opposite) corners[c++] = mesh.tets[e][v];
      if (!atEnd(corners[0]) || !atEnd(corners[1]) || !atEnd(corners[2])) continue;
      const Vec3 p0 = mesh.vertices[corners[0]], p1 = mesh.vertices[corners[1]], p2 = mesh.vertices[corners[2]];
      const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
      const double share = area / bbBinomial(degree + 2, 2);
      for (int a = 0; a < N; ++a)
        if (alpha[a].a[opposite] == 0) weight[body->elementNodes()[N * e + a]] += share;
    }
  double polar = 0.0;
  for (int32_t i = 0; i < body->nodeCount(); ++i)
    polar += weight[i] * (X[3 * i + 1] * X[3 * i + 1] + X[3 * i + 2] * X[3 * i + 2]);

  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  DeformableStepInput in;
  in.dt = 1.0;  // h²K dominates M by ~1e9: each step is a Newton step of the static problem
  in.tasks = tasks.get();
  const double x1 = 1.5 * bar.side, x2 = bar.length - 1.5 * bar.side;
  auto twistAt = [&](double x) {
    double num = 0.0, den = 0.0;
    for (int32_t i = 0; i < body->nodeCount(); ++i) {
      if (std::abs(X[3 * i] - x) > 1e-9) continue;
      const double y = X[3 * i + 1], z = X[3 * i + 2];
      const double uy = body->positions()[3 * i + 1] - y, uz = body->positions()[3 * i + 2] - z;
      num += y * uz - z * uy;
      den += y * y + z * z;
    }
    return num / den;
  };
  double previous = 0.0;
  for (int step = 0; step < 10; ++step) {
    for (int32_t i = 0; i < body->nodeCount(); ++i)
      if (weight[i] > 0.0) {
        const double s = bar.torque * weight[i] / polar;
        body->applyForce(i, Vec3(0.0, -s * X[3 * i + 2], s * X[3 * i + 1]));
      }
    ActorStats stats;
    body->step(in, &stats);
    result.iterations += stats.phase(Phase::Solve).iterations;
    result.measured = twistAt(x2) - twistAt(x1);
    if (step > 0 && std::abs(result.measured - previous) < 1e-7 * std::abs(result.measured)) break;
    previous = result.measured;
  }
  result.analytic = bar.torque * (x2 - x1) / (bar.G() * bar.J());
  return result;
}

// Issue 6: quadratic and cubic within 5% of θ = T L / (G J) (over the measured length).
// 12 x 4 x 4 cells (1152 tets); linear tets are printed for comparison only.
TEST(TorsionValidation, SquareBarTwistMatchesStVenant) {
  const TorsionBar bar;
  std::printf("\n  torsion of a %gx%g m square bar, L = %g m, T = %g N m, twist over x in [%g, %g] m\n", bar.side,
              bar.side, bar.length, bar.torque, 1.5 * bar.side, bar.length - 1.5 * bar.side);
  std::printf("  %-8s %14s %14s %9s %9s\n", "degree", "twist [rad]", "T L/(G J)", "error", "cg iters");
  for (int degree : {1, 2, 3}) {
    const TwistResult r = twistOfBar(bar, degree, 12, 4);
    const double error = std::abs(r.measured - r.analytic) / r.analytic;
    std::printf("  %-8d %14.6e %14.6e %8.2f%% %9d\n", degree, r.measured, r.analytic, 100 * error, r.iterations);
    if (degree > 1) {
      EXPECT_LT(error, 0.05) << "degree " << degree;
    }
  }
}

}  // namespace
}  // namespace vp
