// Cut-cell pressure projection: the operator, MIC(0), divergence after projection, a
// manufactured Neumann solution inside a sphere, hydrostatic rest and budget cuts.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>

#include "collide/face_coverage.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/pressure/mic0_preconditioner.h"
#include "fluid/pressure/pressure_projection.h"
#include "fluid/solids/face_fraction_field.h"
#include "fluid_liquid_test_util.h"
#include "fluid_pressure_scenes.h"
#include "random_values.h"

namespace vp {
namespace {

using testscene::fillSwirl;  // a smooth, non-solenoidal velocity with components of order 1
using testscene::SteppingClock;

constexpr std::array<DomainSide, 6> kClosed{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                            DomainSide::Wall, DomainSide::Wall, DomainSide::Wall};
// Open top (+y): Dirichlet p = 0 there, the operator is nonsingular.
constexpr std::array<DomainSide, 6> kOpenTop{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                             DomainSide::Open, DomainSide::Wall, DomainSide::Wall};

MacGridSpec unitCube(int n) {
  MacGridSpec g;
  g.origin = Eigen::Vector3d::Zero();
  g.h = 1.0 / n;
  g.nx = g.ny = g.nz = n;
  return g;
}

ColliderShape sphereShape(const Eigen::Vector3d& centre, double radius) {
  ColliderShape s;
  s.kind = ShapeKind::Sphere;
  s.radius = radius;
  s.translation = centre;
  return s;
}

using testutil::tiltedBox;

struct Scene {
  MacGrid grid;
  FaceFractionField fractions;
  PreparedCollider collider;
};

void makeScene(const MacGridSpec& spec, const std::array<DomainSide, 6>& sides, const ColliderShape& shape,
               Scene* scene) {
  ASSERT_EQ(initMacGrid(spec, sides, &scene->grid), Status::Ok) << lastError();
  ASSERT_EQ(initFaceFractionField(spec, &scene->fractions), Status::Ok) << lastError();
  ASSERT_EQ(prepareCollider(shape, &scene->collider), Status::Ok) << lastError();
  const PreparedCollider* list[] = {&scene->collider};
  ASSERT_EQ(computeFaceFractions(list, 1, &scene->fractions), Status::Ok) << lastError();
}

double norm2(const Array<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

// Net outflow of every cell, written here from the definition rather than through
// computeNetOutflow (which also builds the right-hand side, so a mistake there would cancel):
// sum over the cell's faces of +-(A_f u_f + (1 - A_f) u_solid,f), + on high faces, with the raw
// collider fractions. Wall faces carry nothing (the scenes' colliders stay off the walls). Faces
// the operator treats as closed (A_f < 1e-6) hold u_f = u_solid after projection, so the raw
// fraction gives the same flux there.
Array<double> netOutflow(const Scene& scene) {
  return testutil::netOutflowByDefinition(scene.grid, scene.fractions);
}

// netOutflow(u) = (dt / (rho h)) (L p - b) cell by cell, and the CG stops at
// |P(b - L p)|_2 <= tol |P b|_2 with |P b|_2 <= (rho h / dt) |netOutflow(u*)|_2, so every cell's
// outflow is below tol * |netOutflow(u*)|_2. The slack covers the CG's recursive residual
// drifting from the true one (round-off, ~1e-14 relative here) and, on floating regions, the
// region mean that the filter removes (the outflows sum to 0 up to round-off).
void expectDivergenceFree(TaskSystem& tasks, Scene& scene, double tolerance) {
  const PressureSolveSettings settings{tolerance, 1000};
  PressureState state;
  PressureSolveStats stats;
  ASSERT_EQ(buildCutCellPoisson(tasks, scene.grid, scene.fractions, &state.poisson), Status::Ok);
  Array<double> initial = netOutflow(scene);
  for (size_t c = 0; c < initial.size(); ++c)
    if (!state.poisson.isFluid(c)) initial[c] = 0.0;
  const double before = norm2(initial);
  ASSERT_GT(before, 1.0);  // the initial field is far from divergence-free
  ASSERT_EQ(projectVelocity(tasks, scene.grid, scene.fractions, 0.01, 1000.0, Deadline(), settings, state,
                            &stats),
            Status::Ok)
      << lastError();
  EXPECT_TRUE(stats.converged);
  EXPECT_FALSE(stats.budgetCut);
  EXPECT_LE(stats.relativeResidual, tolerance);
  const Array<double> after = netOutflow(scene);
  double worst = 0.0;
  for (size_t c = 0; c < after.size(); ++c)
    if (state.poisson.isFluid(c)) worst = std::max(worst, std::fabs(after[c]));
  std::printf("    fluid cells %lld, iterations %d, residual %.3g, max |outflow| %.3g (initial |.|_2 %.3g)\n",
              static_cast<long long>(stats.fluidCells), stats.iterations, stats.relativeResidual, worst, before);
  EXPECT_LE(worst, (1.01 * tolerance + 1e-12) * before);
}

TEST(FluidMacGrid, IndexingAndTrilinearSamplingOfLinearFields) {
  MacGridSpec spec;
  spec.origin = Eigen::Vector3d(-0.3, 0.1, 0.2);
  spec.h = 0.25;
  spec.nx = 4; spec.ny = 5; spec.nz = 3;
  MacGrid grid;
  ASSERT_EQ(initMacGrid(spec, kOpenTop, &grid), Status::Ok);
  EXPECT_EQ(grid.velocity[0].size(), 5u * 5 * 3);
  EXPECT_EQ(grid.velocity[1].size(), 4u * 6 * 3);
  EXPECT_EQ(grid.velocity[2].size(), 4u * 5 * 4);
  EXPECT_EQ(grid.cellIndex(1, 2, 1), 1u + 4 * (2 + 5 * 1));
  EXPECT_TRUE(grid.faceCentre(1, 1, 2, 1).isApprox(spec.origin + 0.25 * Eigen::Vector3d(1.5, 2.0, 1.5)));
  EXPECT_TRUE(grid.isWallFace(0, 0, 1, 1));
  EXPECT_FALSE(grid.isWallFace(1, 1, 5, 1));  // +y is open
  EXPECT_TRUE(grid.isWallFace(1, 1, 0, 1));
  // Trilinear interpolation reproduces affine fields exactly inside the face-centre grid.
  auto field = [](int a, const Eigen::Vector3d& x) { return 0.5 + a + 2.0 * x.x() - 3.0 * x.y() + 0.7 * x.z(); };
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i)
          grid.velocity[a][grid.faceIndex(a, i, j, k)] = field(a, grid.faceCentre(a, i, j, k));
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> t(0.0, 1.0);
  for (int s = 0; s < 50; ++s) {
    // Points at least h/2 inside, where every component's stencil is interior.
    const Eigen::Vector3d inBox = Eigen::Vector3d(3.0, 4.0, 2.0).cwiseProduct(testing_values::randomVector(t, rng));
    const Eigen::Vector3d x = spec.origin + spec.h * (Eigen::Vector3d(0.5, 0.5, 0.5) + inBox);
    const Eigen::Vector3d v = grid.sampleVelocity(x);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(v[a], field(a, x), 1e-12);
  }
  Array<double> scalar(static_cast<size_t>(grid.cellCount()));
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) scalar[grid.cellIndex(i, j, k)] = field(0, grid.cellCentre(i, j, k));
  const Eigen::Vector3d mid = spec.origin + spec.h * Eigen::Vector3d(1.7, 2.2, 1.1);
  EXPECT_NEAR(grid.sampleCellCentred(scalar.data(), mid), field(0, mid), 1e-12);
  // Outside the sample grid the value is clamped to the nearest boundary sample.
  const Eigen::Vector3d far = spec.origin + Eigen::Vector3d(-5.0, 0.5 * spec.h, 0.5 * spec.h);
  EXPECT_NEAR(grid.sampleCellCentred(scalar.data(), far), scalar[grid.cellIndex(0, 0, 0)], 1e-12);
  spec.h = 0.0;
  EXPECT_EQ(initMacGrid(spec, kClosed, &grid), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("h"), std::string::npos);
}

TEST(FluidProjection, DivergenceFreeAroundStaticSphere) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  Scene scene;
  makeScene(unitCube(24), kClosed, sphereShape({0.52, 0.47, 0.49}, 0.27), &scene);
  fillSwirl(scene.grid);
  expectDivergenceFree(*tasks, scene, 1e-8);
}

TEST(FluidProjection, AKeptOperatorGivesBitwiseTheSameProjections) {
  // Three projections in a row around a static sphere, the velocity changed between them as
  // a step would: keeping the operator and multigrid (operatorUnchanged) must give exactly
  // what rebuilding them gives, with either preconditioner.
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  for (PressureSolver solver : {PressureSolver::CutCellMgpcg, PressureSolver::Mic0Pcg}) {
    Scene rebuilt, kept;
    makeScene(unitCube(16), kOpenTop, sphereShape({0.52, 0.47, 0.49}, 0.27), &rebuilt);
    makeScene(unitCube(16), kOpenTop, sphereShape({0.52, 0.47, 0.49}, 0.27), &kept);
    PressureState rebuiltState, keptState;
    for (int step = 0; step < 3; ++step) {
      for (Scene* s : {&rebuilt, &kept}) {
        fillSwirl(s->grid);
        for (double& u : s->grid.velocity[1]) u += 0.3 * step;
      }
      PressureSolveSettings settings{1e-8, 1000};
      settings.solver = solver;
      PressureSolveStats a, b;
      ASSERT_EQ(projectVelocity(*tasks, rebuilt.grid, rebuilt.fractions, 0.01, 1000.0, Deadline(), settings,
                                rebuiltState, &a),
                Status::Ok);
      settings.operatorUnchanged = true;  // also on the first call: nothing is built yet, so it builds
      ASSERT_EQ(projectVelocity(*tasks, kept.grid, kept.fractions, 0.01, 1000.0, Deadline(), settings, keptState, &b),
                Status::Ok);
      EXPECT_EQ(a.iterations, b.iterations);
      EXPECT_EQ(rebuiltState.pressure, keptState.pressure) << "step " << step;
      for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(rebuilt.grid.velocity[axis], kept.grid.velocity[axis]);
    }
  }
}

TEST(FluidProjection, DivergenceFreeAroundMovingBox) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  ColliderShape box = tiltedBox({0.48, 0.45, 0.51});
  box.linearVelocity = Eigen::Vector3d(0.8, -0.5, 0.3);
  box.angularVelocity = Eigen::Vector3d(0.4, 1.0, -0.6);
  Scene scene;
  makeScene(unitCube(24), kOpenTop, box, &scene);
  double maxSolid = 0.0;
  for (int a = 0; a < 3; ++a)
    for (double v : scene.fractions.solidVelocity[a]) maxSolid = std::max(maxSolid, std::fabs(v));
  ASSERT_GT(maxSolid, 0.3);  // the solid terms are really exercised
  fillSwirl(scene.grid);
  expectDivergenceFree(*tasks, scene, 1e-8);
  // Closed faces carry the solid's velocity.
  int closed = 0;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = scene.grid.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const size_t f = scene.grid.faceIndex(a, i, j, k);
          if (scene.grid.isWallFace(a, i, j, k) || effectiveOpenFraction(scene.grid, scene.fractions, a, i, j, k) > 0.0)
            continue;
          EXPECT_EQ(scene.grid.velocity[a][f], scene.fractions.solidVelocity[a][f]);
          ++closed;
        }
  }
  EXPECT_GT(closed, 0);
}

TEST(FluidProjection, OperatorAndMic0AreSymmetricPositive) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  Scene scene;
  makeScene(unitCube(16), kOpenTop, tiltedBox({0.5, 0.5, 0.5}), &scene);
  CutCellPoisson op;
  ASSERT_EQ(buildCutCellPoisson(*tasks, scene.grid, scene.fractions, &op), Status::Ok);
  ASSERT_EQ(op.regionFloating.size(), 1u);
  EXPECT_EQ(op.regionFloating[0], 0);  // the open top makes it definite
  EXPECT_LT(op.fluidCellCount, scene.grid.cellCount());  // the box swallows whole cells
  Mic0Preconditioner mic;
  ASSERT_EQ(buildMic0Preconditioner(op, Mic0Settings{}, &mic), Status::Ok);
  const size_t n = static_cast<size_t>(scene.grid.cellCount());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Array<double> x(n), y(n), ax(n), ay(n);
  auto dot = [](const Array<double>& a, const Array<double>& b) {
    double s = 0.0;
    for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
    return s;
  };
  for (int trial = 0; trial < 5; ++trial) {
    for (size_t c = 0; c < n; ++c) {
      x[c] = op.isFluid(c) ? u(rng) : 0.0;
      y[c] = op.isFluid(c) ? u(rng) : 0.0;
    }
    applyCutCellPoisson(*tasks, op, x.data(), ax.data());
    applyCutCellPoisson(*tasks, op, y.data(), ay.data());
    const double scale = std::sqrt(dot(x, x) * dot(ay, ay));
    // Same products summed in another order: round-off only.
    EXPECT_NEAR(dot(x, ay), dot(y, ax), 1e-12 * scale);
    EXPECT_GT(dot(x, ax), 0.0);
    applyMic0Preconditioner(op, mic, x.data(), ax.data());
    applyMic0Preconditioner(op, mic, y.data(), ay.data());
    EXPECT_NEAR(dot(x, ay), dot(y, ax), 1e-12 * std::sqrt(dot(x, x) * dot(ay, ay)));
    EXPECT_GT(dot(x, ax), 0.0);
  }
  // Smallest eigenvalue > 0: the Rayleigh quotient of the smoothest mode (a constant, which a
  // floating region would map to 0) stays clearly positive with the Dirichlet top.
  for (size_t c = 0; c < n; ++c) x[c] = op.isFluid(c) ? 1.0 : 0.0;
  applyCutCellPoisson(*tasks, op, x.data(), ax.data());
  EXPECT_GT(dot(x, ax) / dot(x, x), 1e-3);
  // In a closed box the constant is the null vector: L 1 = 0 exactly.
  Scene closed;
  makeScene(unitCube(16), kClosed, tiltedBox({0.5, 0.5, 0.5}), &closed);
  ASSERT_EQ(buildCutCellPoisson(*tasks, closed.grid, closed.fractions, &op), Status::Ok);
  ASSERT_EQ(op.regionFloating.size(), 1u);
  EXPECT_EQ(op.regionFloating[0], 1);
  applyCutCellPoisson(*tasks, op, x.data(), ax.data());
  for (size_t c = 0; c < n; ++c) ASSERT_NEAR(ax[c], 0.0, 1e-13);
}


// Manufactured solution p = exp(x) sin(y) (harmonic) inside a sphere. The fluid is the inside:
// the sphere's face fractions are inverted, so its surface is a cut-cell Neumann boundary,
// the condition the operator implies there. Finite-volume balance of cell c with the flux
// dp/dn on the covered parts of its faces standing for the flux through the curved boundary
// (exact for harmonic p: grad p is divergence-free, so the flux out of the cell's solid part
// is 0), with both fluxes evaluated at face centres:
//     (L p)_c = h * sum_f +-(1 - A_f) d_a p(face centre)
// The pure Neumann problem fixes p up to a constant: errors are measured after removing the
// mean difference.
struct ManufacturedError {
  double maxNorm = 0.0, l2 = 0.0;
  double maxNormCentreInFluid = 0.0;  // over cells whose centre lies inside the sphere
  int iterations = 0;
  double residual = 0.0;
};

ManufacturedError manufacturedSphereError(TaskSystem& tasks, int n) {
  ManufacturedError result;
  Scene scene;
  makeScene(unitCube(n), kClosed, sphereShape({0.503, 0.497, 0.501}, 0.45), &scene);
  for (int a = 0; a < 3; ++a)
    for (double& open : scene.fractions.open[a]) open = 1.0 - open;
  CutCellPoisson op;
  EXPECT_EQ(buildCutCellPoisson(tasks, scene.grid, scene.fractions, &op), Status::Ok);
  EXPECT_EQ(op.regionFloating.size(), 1u);
  Mic0Preconditioner mic;
  EXPECT_EQ(buildMic0Preconditioner(op, Mic0Settings{}, &mic), Status::Ok);
  const MacGrid& grid = scene.grid;
  const double h = grid.spec.h;
  auto exact = [](const Eigen::Vector3d& x) { return std::exp(x.x()) * std::sin(x.y()); };
  auto gradient = [](int a, const Eigen::Vector3d& x) {
    return a == 0 ? std::exp(x.x()) * std::sin(x.y()) : a == 1 ? std::exp(x.x()) * std::cos(x.y()) : 0.0;
  };
  const size_t cells = static_cast<size_t>(grid.cellCount());
  Array<double> b(cells, 0.0), p(cells, 0.0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const size_t c = grid.cellIndex(i, j, k);
        if (!op.isFluid(c)) continue;
        double sum = 0.0;
        for (int a = 0; a < 3; ++a)
          for (int high = 0; high < 2; ++high) {
            Eigen::Vector3i f(i, j, k);
            f[a] += high;
            const double covered = 1.0 - effectiveOpenFraction(grid, scene.fractions, a, f.x(), f.y(), f.z());
            const double flux = covered * gradient(a, grid.faceCentre(a, f.x(), f.y(), f.z()));
            sum += high ? flux : -flux;
          }
        b[c] = h * sum;
      }
  LinearSystem system;
  system.size = static_cast<int64_t>(cells);
  system.apply = [&](const double* x, double* y) { applyCutCellPoisson(tasks, op, x, y); };
  system.precondition = [&](const double* r, double* z) { applyMic0Preconditioner(op, mic, r, z); };
  system.filter = [&](double* v) { filterCutCellPoisson(tasks, op, v); };
  CgSettings settings;
  settings.relativeTolerance = 1e-11;  // far below the discretization error at 64^3 (~1e-5)
  settings.maxIterations = 1000;
  CgWorkspace work;
  const CgResult cg = solveConjugateGradient(tasks, system, b.data(), p.data(), settings, Deadline(), work);
  EXPECT_TRUE(cg.converged);
  result.iterations = cg.iterations;
  result.residual = cg.relativeResidual;
  Array<double> error(cells, 0.0);
  Array<uint8_t> centreInFluid(cells, 0);
  double meanError = 0.0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const size_t c = grid.cellIndex(i, j, k);
        if (!op.isFluid(c)) continue;
        error[c] = p[c] - exact(grid.cellCentre(i, j, k));
        centreInFluid[c] = (grid.cellCentre(i, j, k) - scene.collider.translation).norm() < 0.45;
        meanError += error[c];
      }
  meanError /= static_cast<double>(op.fluidCellCount);
  double sumSquares = 0.0;
  for (size_t c = 0; c < cells; ++c) {
    if (!op.isFluid(c)) continue;
    const double e = error[c] - meanError;
    result.maxNorm = std::max(result.maxNorm, std::fabs(e));
    if (centreInFluid[c]) result.maxNormCentreInFluid = std::max(result.maxNormCentreInFluid, std::fabs(e));
    sumSquares += e * e;
  }
  result.l2 = std::sqrt(sumSquares / static_cast<double>(op.fluidCellCount));  // RMS over cells
  return result;
}

TEST(FluidPoisson, ManufacturedNeumannSolutionInsideSphereConvergesAtSecondOrder) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const int sizes[] = {16, 32, 64};
  ManufacturedError errors[3];
  for (int s = 0; s < 3; ++s) {
    errors[s] = manufacturedSphereError(*tasks, sizes[s]);
    std::printf("    %d^3: max %.3e  max(centre in fluid) %.3e  L2 %.3e  (%d iterations, residual %.2e)\n",
                sizes[s], errors[s].maxNorm, errors[s].maxNormCentreInFluid, errors[s].l2, errors[s].iterations,
                errors[s].residual);
  }
  for (int s = 0; s + 1 < 3; ++s) {
    const double maxOrder = std::log2(errors[s].maxNorm / errors[s + 1].maxNorm);
    const double insideOrder = std::log2(errors[s].maxNormCentreInFluid / errors[s + 1].maxNormCentreInFluid);
    const double l2Order = std::log2(errors[s].l2 / errors[s + 1].l2);
    std::printf("    order %d -> %d: max %.2f  max(centre in fluid) %.2f  L2 %.2f\n", sizes[s], sizes[s + 1], maxOrder,
                insideOrder, l2Order);
    EXPECT_GE(l2Order, 1.8);
    EXPECT_GE(insideOrder, 1.8);
  }
  // The max norm over ALL fluid cells does not converge (measured 3.2e-3, 7.3e-4, 8.8e-4 for
  // 16, 32, 64): it sits on sliver cells whose centre lies outside the sphere and whose open
  // faces are tiny (diagonal ~1e-6 at 64^3). Their sample point is up to h sqrt(3)/2 away from
  // the fluid it stands for, and their whole balance is the two-point flux through a face
  // whose open part is a corner, not the centre the difference assumes: an O(1) relative
  // error on a cell that carries almost no fluid. So second order is asserted in L2 (RMS over
  // cells) and in the max norm over cells whose centre is in the fluid, and the all-cell max
  // norm only has to stay bounded (no blow-up under refinement). Volume-weighted sampling or
  // merging slivers into a neighbour would fix it; not done here.
  EXPECT_LT(errors[2].maxNorm, 2e-3);
}

TEST(FluidProjection, HydrostaticRestWithTiltedBoxInClosedContainer) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  Scene scene;
  makeScene(unitCube(20), kClosed, tiltedBox({0.47, 0.38, 0.52}), &scene);
  const double g = 9.81, dt = 0.01, rho = 1000.0;
  for (double& v : scene.grid.velocity[1]) v -= dt * g;
  PressureState state;
  PressureSolveStats stats;
  ASSERT_EQ(projectVelocity(*tasks, scene.grid, scene.fractions, dt, rho, Deadline(), PressureSolveSettings{1e-10, 1000},
                            state, &stats),
            Status::Ok);
  EXPECT_TRUE(stats.converged);
  double maxSpeed = 0.0;
  for (int a = 0; a < 3; ++a)
    for (double v : scene.grid.velocity[a]) maxSpeed = std::max(maxSpeed, std::fabs(v));
  // p = rho g (H - y) is the discrete solution exactly (L of a linear p matches the rhs face by
  // face), so what remains is the solver's residual.
  EXPECT_LT(maxSpeed, 1e-6 * g * dt);
  // The closed container fixes p up to a constant: compare against the hydrostatic profile
  // after matching means, relative to the pressure scale rho g H.
  const MacGrid& grid = scene.grid;
  double meanP = 0.0, meanExact = 0.0;
  int64_t count = 0;
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) {
        const size_t c = grid.cellIndex(i, j, k);
        if (!state.poisson.isFluid(c)) continue;
        meanP += state.pressure[c];
        meanExact += rho * g * (1.0 - grid.cellCentre(i, j, k).y());
        ++count;
      }
  meanP /= count;
  meanExact /= count;
  double worst = 0.0;
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) {
        const size_t c = grid.cellIndex(i, j, k);
        if (!state.poisson.isFluid(c)) continue;
        const double exact = rho * g * (1.0 - grid.cellCentre(i, j, k).y()) - meanExact;
        worst = std::max(worst, std::fabs(state.pressure[c] - meanP - exact));
      }
  std::printf("    iterations %d, residual %.2e, max |u| %.2e, max pressure error %.2e Pa\n", stats.iterations,
              stats.relativeResidual, maxSpeed, worst);
  EXPECT_LT(worst, 1e-6 * rho * g);
}

TEST(FluidProjection, BudgetCutSolveConvergesOverFramesByWarmStart) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  Scene scene;
  makeScene(unitCube(16), kOpenTop, sphereShape({0.5, 0.45, 0.5}, 0.25), &scene);
  fillSwirl(scene.grid);
  const MacGrid initial = scene.grid;
  // MIC(0)-PCG's budget behaviour (the multigrid converges within two 5 ms frames here; its
  // budget test is in fluid_multigrid_test.cpp).
  const PressureSolveSettings settings{1e-8, 1000, PressureSolver::Mic0Pcg};
  SteppingClock fake;
  PressureState state;
  PressureSolveStats stats;
  double firstResidual = 0.0;
  int frames = 0;
  for (; frames < 40; ++frames) {
    scene.grid = initial;  // the same intermediate velocity every frame
    ASSERT_EQ(projectVelocity(*tasks, scene.grid, scene.fractions, 0.01, 1000.0, Deadline(fake.clock(), 5.0),
                              settings, state, &stats),
              Status::Ok);
    if (frames == 0) {
      firstResidual = stats.relativeResidual;
      EXPECT_TRUE(stats.budgetCut);
      EXPECT_FALSE(stats.converged);
      EXPECT_LE(stats.iterations, 5);
    }
    if (stats.converged) break;
    EXPECT_TRUE(stats.budgetCut);
  }
  std::printf("    first frame residual %.2e, converged after %d frames\n", firstResidual, frames + 1);
  EXPECT_TRUE(stats.converged);
  EXPECT_LE(stats.relativeResidual, 1e-8);
  EXPECT_GT(frames, 1);
  // Without the warm start every frame is the first one again.
  PressureState cold;
  scene.grid = initial;
  ASSERT_EQ(projectVelocity(*tasks, scene.grid, scene.fractions, 0.01, 1000.0, Deadline(fake.clock(), 5.0), settings,
                            cold, &stats),
            Status::Ok);
  EXPECT_DOUBLE_EQ(stats.relativeResidual, firstResidual);
}

TEST(FluidProjection, RejectsBadArguments) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  Scene scene;
  makeScene(unitCube(4), kClosed, sphereShape({0.5, 0.5, 0.5}, 0.2), &scene);
  PressureState state;
  EXPECT_EQ(projectVelocity(*tasks, scene.grid, scene.fractions, 0.0, 1000.0, Deadline(), {}, state, nullptr),
            Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("dt"), std::string::npos);
  EXPECT_EQ(projectVelocity(*tasks, scene.grid, scene.fractions, 0.01, -1.0, Deadline(), {}, state, nullptr),
            Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("density"), std::string::npos);
  FaceFractionField other;
  ASSERT_EQ(initFaceFractionField(unitCube(5), &other), Status::Ok);
  EXPECT_EQ(projectVelocity(*tasks, scene.grid, other, 0.01, 1000.0, Deadline(), {}, state, nullptr),
            Status::InvalidArgument);
}

}  // namespace
}  // namespace vp
