// p-multigrid on real deformable step matrices (cubic and quadratic beams, clamped, some
// nodes under a sliding-contact filter): the cycle is a symmetric positive preconditioner,
// its coarse operators are the constrained Galerkin products, PCG with it reaches the same
// solution as block-Jacobi PCG, and it converges as a solver on its own.
#include "linalg/p_multigrid.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "core/budget_clock.h"
#include "deform/degree_hierarchy.h"
#include "deform/degree_level_assembly.h"
#include "deform/deformable_body.h"
#include "deform_test_util.h"
#include "geometry/box_tet_mesh.h"
#include "linalg/richardson_iteration.h"

namespace vp {
namespace {

using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

struct BeamSystem {
  std::unique_ptr<DeformableBody> body;
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  std::vector<double> filters;
  DegreeHierarchy hierarchy;
  // Re-discretized coarse levels (empty: Galerkin), assembled from the step's gradient pairs.
  mutable std::vector<DegreeLevelAssembly> rediscretized;
  double massScale = 1.0;

  BeamSystem(int degree, std::array<int, 3> cells, const std::vector<int>& degrees,
             PMultigridCoarseOperator coarse = PMultigridCoarseOperator::Galerkin) {
    DeformableDesc d;
    d.degree = degree;
    d.mesh = makeBoxTetMesh(cells, Vec3(cells[0], cells[1], cells[2]), Vec3::Zero());
    d.material.youngsModulus = 1e8;
    d.solver.preconditioner = Preconditioner::BlockJacobi;  // the test drives its own cycle
    EXPECT_EQ(DeformableBody::create(d, &body), Status::Ok) << lastError();
    deform_test::pinNodesAtX(*body, 0.0);
    DeformableStepInput in;
    in.tasks = tasks.get();
    in.gravity = Vec3(0, -9.81, 0);
    ActorStats stats;
    body->step(in, &stats);
    massScale = 1.0 + in.dt * d.material.massDamping;
    // Pinned: 0; nodes on the top face (y = max) slide on a tilted plane: I − nnᵀ.
    const Vec3 n = Vec3(0.3, 1.0, -0.2).normalized();
    const Mat3R slide = Mat3R::Identity() - n * n.transpose();
    filters.assign(9 * static_cast<size_t>(body->nodeCount()), 0.0);
    for (int32_t i = 0; i < body->nodeCount(); ++i) {
      Eigen::Map<Mat3R> F(&filters[9 * i]);
      if (body->pinned(i)) F.setZero();
      else if (body->restPositions()[3 * i + 1] == cells[1]) F = slide;
      else F.setIdentity();
    }
    EXPECT_EQ(buildDegreeHierarchy(degrees, body->elementNodes().data(), body->elementCount(), body->nodeCount(),
                                   &hierarchy),
              Status::Ok);
    if (coarse == PMultigridCoarseOperator::Rediscretized) {
      rediscretized.resize(hierarchy.levels.size() - 1);
      for (size_t l = 1; l < hierarchy.levels.size(); ++l)
        rediscretized[l - 1].build(hierarchy.levels[l], degree, body->restVolumes().data(), body->elementCount(),
                                   d.material.density);
    }
  }
  // Only the stiffness from now on (scale 1, no mass): what the exactness checks compare.
  void keepStiffnessOnly() {
    Array<double> forces;
    body->elasticForces(*tasks, &forces);
    massScale = 0.0;
  }
  int64_t size() const { return 3 * static_cast<int64_t>(body->nodeCount()); }
  void filter(double* v) const {
    for (int32_t i = 0; i < body->nodeCount(); ++i) {
      Eigen::Map<Eigen::Vector3d> vi(v + 3 * i);
      vi = Eigen::Map<const Mat3R>(&filters[9 * i]) * vi;
    }
  }
  std::vector<double> randomFiltered(std::mt19937& rng) const {
    std::normal_distribution<double> g;
    std::vector<double> v(static_cast<size_t>(size()));
    for (double& x : v) x = g(rng);
    filter(v.data());
    return v;
  }
  void setUp(PMultigrid* mg, const PMultigridSettings& settings = {}) const {
    std::vector<BlockSparseMatrix<double>*> coarse;
    for (DegreeLevelAssembly& level : rediscretized) coarse.push_back(&level.matrix());
    mg->build(body->stepMatrix(), hierarchy.prolongations, settings, coarse);
    update(mg);
  }
  void update(PMultigrid* mg) const {
    for (DegreeLevelAssembly& level : rediscretized)
      level.assemble(*tasks, body->elementGradientPairs().data(), massScale);
    mg->update(*tasks, body->stepMatrix(), body->positions().data(), filters.data());
  }
  LinearSystem system(std::function<void(const double*, double*)> precondition) const {
    LinearSystem s;
    s.size = size();
    s.apply = [this](const double* x, double* y) { body->stepMatrix().multiply(*tasks, x, y); };
    s.precondition = std::move(precondition);
    s.filter = [this](double* v) { filter(v); };
    return s;
  }
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

void expectSymmetricPositive(const BeamSystem& sys, const PMultigridSettings& settings, const char* what) {
  PMultigrid mg;
  sys.setUp(&mg, settings);
  std::mt19937 rng(2);
  for (int trial = 0; trial < 4; ++trial) {
    const std::vector<double> x = sys.randomFiltered(rng), y = sys.randomFiltered(rng);
    std::vector<double> Mx(x.size()), My(y.size());
    mg.apply(*sys.tasks, x.data(), Mx.data());
    mg.apply(*sys.tasks, y.data(), My.data());
    const double a = dot(x, My), b = dot(y, Mx);
    EXPECT_NEAR(a, b, 1e-11 * (std::abs(a) + std::abs(b) + dot(x, Mx) + dot(y, My))) << what;
    EXPECT_GT(dot(x, Mx), 0.0) << what;
    EXPECT_GT(dot(y, My), 0.0) << what;
  }
}

// x·My = y·Mx to round-off and x·Mx > 0 on the constrained space, for every hierarchy and
// both smoothers: CG's requirements on a preconditioner.
TEST(PMultigrid, VCycleIsSymmetricAndPositive) {
  for (PMultigridCoarseOperator coarse : {PMultigridCoarseOperator::Galerkin, PMultigridCoarseOperator::Rediscretized}) {
    SCOPED_TRACE(coarse == PMultigridCoarseOperator::Galerkin ? "Galerkin" : "re-discretized");
    const BeamSystem cubic321(3, {6, 2, 2}, {3, 2, 1}, coarse), cubic31(3, {6, 2, 2}, {3, 1}, coarse),
        quad21(2, {6, 2, 2}, {2, 1}, coarse);
    for (PMultigridSmoother smoother : {PMultigridSmoother::Chebyshev, PMultigridSmoother::DampedJacobi}) {
      PMultigridSettings s;
      s.smoother = smoother;
      expectSymmetricPositive(cubic321, s, "3-2-1");
      expectSymmetricPositive(cubic31, s, "3-1");
      expectSymmetricPositive(quad21, s, "2-1");
      s.coarseCycles = 2;
      s.sweeps = 3;
      expectSymmetricPositive(cubic321, s, "3-2-1, 3 sweeps, 2 coarse cycles");
    }
  }
}

// Each coarse operator is P̃ᵀ A P̃ with P̃ = F_f P F_c, checked densely on a small cubic beam.
TEST(PMultigrid, CoarseOperatorsAreConstrainedGalerkinProducts) {
  const BeamSystem sys(3, {3, 1, 1}, {3, 2, 1});
  PMultigrid mg;
  sys.setUp(&mg);
  ASSERT_EQ(mg.levelCount(), 3);
  Eigen::MatrixXd A = deform_test::denseMatrix(mg.levelMatrix(0));
  Eigen::MatrixXd Ff = Eigen::MatrixXd::Zero(A.rows(), A.cols());
  for (int32_t i = 0; i < sys.body->nodeCount(); ++i) Ff.block<3, 3>(3 * i, 3 * i) = Eigen::Map<const Mat3R>(&sys.filters[9 * i]);
  for (int l = 1; l < 3; ++l) {
    const NodeProlongation& P = sys.hierarchy.prolongations[l - 1];
    const Eigen::MatrixXd Pd = deform_test::denseProlongation(P);
    // The coarse filter projects onto the span of its fine readers' allowed directions.
    Eigen::MatrixXd Fc = Eigen::MatrixXd::Zero(3 * P.coarseNodes, 3 * P.coarseNodes);
    for (int32_t a = 0; a < P.coarseNodes; ++a) {
      Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
      for (int32_t i = 0; i < P.fineNodes; ++i)
        for (int32_t k = P.rowStart[i]; k < P.rowStart[i + 1]; ++k)
          if (P.columns[k] == a) S += Ff.block<3, 3>(3 * i, 3 * i);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
      for (int c = 0; c < 3; ++c)
        if (eig.eigenvalues()[c] > 1e-9 * std::max(eig.eigenvalues().maxCoeff(), 1e-300))
          Fc.block<3, 3>(3 * a, 3 * a) += eig.eigenvectors().col(c) * eig.eigenvectors().col(c).transpose();
    }
    const Eigen::MatrixXd Pt = Ff * Pd * Fc;
    const Eigen::MatrixXd expected = Pt.transpose() * A * Pt;
    // (Filtered-out directions carry a positive diagonal that no cycle sees: compare on F_c.)
    const Eigen::MatrixXd actual = Fc * deform_test::denseMatrix(mg.levelMatrix(l)) * Fc;
    EXPECT_LT((actual - expected).norm(), 1e-12 * expected.norm()) << "level " << l;
    A = expected;
    Ff = Fc;
  }
}

// Re-discretized levels under the same constraints (pinned face, a face sliding on a tilted
// plane): a coarse node may move only where all its fine readers may (F_c: the intersection of
// their ranges), so P F_c maps into the constrained fine space, and the constrained operator
// is the Galerkin operator of that conforming coarse space, (P F_c)ᵀ A (P F_c). Checked densely
// on the stiffness alone (scale 1, no mass), where re-discretization is exact.
TEST(PMultigrid, RediscretizedCoarseOperatorsAreGalerkinOnTheConformingCoarseSpace) {
  for (const std::vector<int>& degrees : {std::vector<int>{3, 2, 1}, std::vector<int>{2, 1}}) {
    BeamSystem sys(degrees[0], {3, 1, 1}, degrees, PMultigridCoarseOperator::Rediscretized);
    sys.keepStiffnessOnly();
    PMultigrid mg;
    sys.setUp(&mg);
    ASSERT_TRUE(mg.rediscretized());
    ASSERT_EQ(mg.levelCount(), static_cast<int>(degrees.size()));
    Eigen::MatrixXd Ff = Eigen::MatrixXd::Zero(sys.size(), sys.size());
    for (int32_t i = 0; i < sys.body->nodeCount(); ++i) Ff.block<3, 3>(3 * i, 3 * i) = Eigen::Map<const Mat3R>(&sys.filters[9 * i]);
    Eigen::MatrixXd A = Ff * deform_test::denseMatrix(mg.levelMatrix(0)) * Ff;
    for (int l = 1; l < mg.levelCount(); ++l) {
      const NodeProlongation& P = sys.hierarchy.prolongations[l - 1];
      const Eigen::MatrixXd Pd = deform_test::denseProlongation(P);
      // F_c: the null space of Σ (I − F_i) over the fine readers i of each coarse node.
      Eigen::MatrixXd Fc = Eigen::MatrixXd::Zero(3 * P.coarseNodes, 3 * P.coarseNodes);
      int constrainedCoarse = 0;
      for (int32_t a = 0; a < P.coarseNodes; ++a) {
        Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
        for (int32_t i = 0; i < P.fineNodes; ++i)
          for (int32_t k = P.rowStart[i]; k < P.rowStart[i + 1]; ++k)
            if (P.columns[k] == a) S += Eigen::Matrix3d::Identity() - Ff.block<3, 3>(3 * i, 3 * i);
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
        for (int c = 0; c < 3; ++c)
          if (eig.eigenvalues()[c] < 1e-9) Fc.block<3, 3>(3 * a, 3 * a) += eig.eigenvectors().col(c) * eig.eigenvectors().col(c).transpose();
        constrainedCoarse += !Fc.block<3, 3>(3 * a, 3 * a).isIdentity(1e-12);
      }
      EXPECT_GT(constrainedCoarse, 0) << "level " << l;
      const Eigen::MatrixXd conforming = Pd * Fc;
      EXPECT_LT((Ff * conforming - conforming).norm(), 1e-12 * conforming.norm()) << "P F_c leaves the constrained space";
      const Eigen::MatrixXd expected = conforming.transpose() * A * conforming;
      // Times F_c on the right only: the level's own filter must be F_c, or rows outside it
      // remain (the σ it puts on filtered-out directions is block diagonal and drops out).
      const Eigen::MatrixXd actual = deform_test::denseMatrix(mg.levelMatrix(l)) * Fc;
      EXPECT_LT((actual - expected).norm(), 1e-12 * expected.norm()) << "level " << l;
      A = expected;
      Ff = Fc;
    }
  }
}

// PCG with the V-cycle reaches the block-Jacobi PCG solution, in far fewer iterations.
TEST(PMultigrid, PreconditionedCgMatchesBlockJacobiPcg) {
  const BeamSystem sys(3, {8, 2, 2}, {3, 2, 1});
  PMultigrid mg;
  sys.setUp(&mg);
  std::mt19937 rng(5);
  const std::vector<double> b = sys.randomFiltered(rng);
  const BlockSparseMatrix<double>& A = sys.body->stepMatrix();
  std::vector<double> blockInverse(9 * static_cast<size_t>(A.blockRows));
  for (int32_t i = 0; i < A.blockRows; ++i)
    Eigen::Map<Mat3R>{&blockInverse[9 * i]} = Eigen::Map<const Mat3R>(&A.values[9 * static_cast<int64_t>(A.diagonal[i])]).inverse();
  const LinearSystem jacobi = sys.system([&](const double* r, double* z) {
    for (int32_t i = 0; i < A.blockRows; ++i)
      Eigen::Map<Eigen::Vector3d>(z + 3 * i) = Eigen::Map<const Mat3R>(&blockInverse[9 * i]) * Eigen::Map<const Eigen::Vector3d>(r + 3 * i);
  });
  const LinearSystem pmg = sys.system([&](const double* r, double* z) { mg.apply(*sys.tasks, r, z); });
  std::vector<double> xj(b.size(), 0.0), xp(b.size(), 0.0);
  CgWorkspace work;
  const CgSettings settings{1e-10, 20000};
  const CgResult rj = solveConjugateGradient(*sys.tasks, jacobi, b.data(), xj.data(), settings, Deadline(), work);
  const CgResult rp = solveConjugateGradient(*sys.tasks, pmg, b.data(), xp.data(), settings, Deadline(), work);
  ASSERT_TRUE(rj.converged);
  ASSERT_TRUE(rp.converged);
  double diff = 0.0;
  for (size_t k = 0; k < b.size(); ++k) diff += (xj[k] - xp[k]) * (xj[k] - xp[k]);
  // Both residuals are below 1e-10 |b|; the solutions then agree to about cond(A) · 1e-10.
  EXPECT_LT(std::sqrt(diff), 1e-5 * std::sqrt(dot(xj, xj)));
  EXPECT_LT(3 * rp.iterations, rj.iterations) << "pmg " << rp.iterations << ", block-Jacobi " << rj.iterations;
}

// The cycle alone (x += V(b − A x)) converges: its error propagation is a contraction.
TEST(PMultigrid, ConvergesAsAStandaloneSolver) {
  for (int run = 0; run < 4; ++run) {
    const int degree = 2 + run % 2;
    const PMultigridCoarseOperator coarse = run < 2 ? PMultigridCoarseOperator::Galerkin : PMultigridCoarseOperator::Rediscretized;
    const char* kind = run < 2 ? "Galerkin" : "re-discretized";
    const BeamSystem sys(degree, {8, 2, 2}, degree == 3 ? std::vector<int>{3, 2, 1} : std::vector<int>{2, 1}, coarse);
    PMultigrid mg;
    sys.setUp(&mg);
    std::mt19937 rng(6);
    const std::vector<double> b = sys.randomFiltered(rng);
    std::vector<double> x(b.size(), 0.0);
    CgWorkspace work;
    const LinearSystem pmg = sys.system([&](const double* r, double* z) { mg.apply(*sys.tasks, r, z); });
    const CgResult result = solveRichardson(*sys.tasks, pmg, b.data(), x.data(), CgSettings{1e-8, 500}, Deadline(), work);
    EXPECT_TRUE(result.converged) << kind << ", degree " << degree << ": residual " << result.relativeResidual;
    // And the iterate really is a solution: recompute its residual independently.
    std::vector<double> Ax(b.size());
    sys.body->stepMatrix().multiply(*sys.tasks, x.data(), Ax.data());
    for (size_t k = 0; k < b.size(); ++k) Ax[k] = b[k] - Ax[k];
    sys.filter(Ax.data());
    EXPECT_LE(std::sqrt(dot(Ax, Ax)), 1e-8 * std::sqrt(dot(b, b))) << kind;
    std::printf("  standalone p-multigrid (%s), degree %d: %d cycles to 1e-8\n", kind, degree, result.iterations);
  }
}

// In the actor: the PMultigrid preconditioner, with either kind of coarse operator, gives the
// same step as block-Jacobi.
TEST(PMultigrid, ActorStepMatchesBlockJacobi) {
  auto run = [](Preconditioner pc, int* iterations,
                PMultigridCoarseOperator coarse = PMultigridCoarseOperator::Galerkin) {
    DeformableDesc d;
    d.degree = 3;
    d.mesh = makeBoxTetMesh({8, 2, 2}, Vec3(4, 1, 1), Vec3::Zero());
    d.material.youngsModulus = 1e7;
    d.solver.tolerance = 1e-10;
    d.solver.maxIterations = 20000;
    d.solver.preconditioner = pc;
    d.solver.pMultigridCoarseOperator = coarse;
    std::unique_ptr<DeformableBody> body;
    EXPECT_EQ(DeformableBody::create(d, &body), Status::Ok);
    EXPECT_EQ(body->preconditioner(), pc);
    deform_test::pinNodesAtX(*body, 0.0);
    auto tasks = TaskSystem::create(TaskHooks{}, 2);
    DeformableStepInput in;
    in.tasks = tasks.get();
    in.gravity = Vec3(0, -9.81, 0);
    *iterations = 0;
    for (int step = 0; step < 3; ++step) {
      ActorStats stats;
      body->step(in, &stats);
      *iterations += stats.phase(Phase::Solve).iterations;
    }
    std::vector<double> displacement(body->positions().size());
    for (size_t k = 0; k < displacement.size(); ++k) displacement[k] = body->positions()[k] - body->restPositions()[k];
    return displacement;
  };
  int itJ = 0;
  const std::vector<double> xj = run(Preconditioner::BlockJacobi, &itJ);
  for (PMultigridCoarseOperator coarse : {PMultigridCoarseOperator::Galerkin, PMultigridCoarseOperator::Rediscretized}) {
    int itP = 0;
    const std::vector<double> xp = run(Preconditioner::PMultigrid, &itP, coarse);
    double diff = 0.0, motion = 0.0;
    for (size_t k = 0; k < xj.size(); ++k) diff = std::max(diff, std::abs(xj[k] - xp[k])), motion = std::max(motion, std::abs(xj[k]));
    ASSERT_GT(motion, 0.0);
    // Both solves stop at 1e-10 relative residual; three steps agree far below that in shape.
    EXPECT_LT(diff, 1e-6 * motion) << static_cast<int>(coarse);
    EXPECT_LT(itP, itJ) << static_cast<int>(coarse);
  }
}

}  // namespace
}  // namespace vp
