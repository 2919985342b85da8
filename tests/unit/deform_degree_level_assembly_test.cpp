// Re-discretized p-multigrid levels: the stiffness assembled at a coarser degree with the fine
// level's element rotations is the Galerkin product of the fine stiffness (degree elevation
// is exact), the mass is the lumped mass of that degree, and the actor's solve with these
// levels reaches the block-Jacobi solution.
#include "deform/degree_level_assembly.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "deform/deformable_body.h"
#include "deform_test_util.h"
#include "geometry/box_tet_mesh.h"
#include "random_values.h"

namespace vp {
namespace {

using deform_test::denseMatrix;
using deform_test::denseProlongation;

struct DeformedBody {
  std::unique_ptr<DeformableBody> body;
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);

  // A jittered box, at rest (every rotation I) or with every node moved by a rotation plus a
  // random non-affine displacement, so each element gets its own rotation; the stiffness
  // (scale 1, no mass) and the gradient pairs of that state are assembled.
  DeformedBody(int degree, bool deformed) {
    DeformableDesc d;
    d.degree = degree;
    d.mesh = makeBoxTetMesh({3, 2, 1}, Vec3(3, 2, 1), Vec3::Zero());
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    for (Vec3& v : d.mesh.vertices) v += testing_values::randomVector(u, rng);
    d.material.youngsModulus = 1e6;
    d.material.poissonRatio = 0.45;
    d.solver.preconditioner = Preconditioner::BlockJacobi;
    EXPECT_EQ(DeformableBody::create(d, &body), Status::Ok) << lastError();
    Array<double> forces;
    if (!deformed) {
      body->elasticForces(*tasks, &forces);
      return;
    }
    const Eigen::Matrix3d R = deform_test::randomRotation(rng);
    std::uniform_real_distribution<double> bend(-0.2, 0.2);
    std::vector<double> x(body->restPositions().begin(), body->restPositions().end());
    for (size_t i = 0; i < x.size() / 3; ++i) {
      Eigen::Vector3d p(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
      const double dy = bend(rng), dz = bend(rng);  // one a statement: a fixed order
      p += Eigen::Vector3d(0.3 * p.y() * p.y(), dy, dz);
      p = R * p;
      for (int k = 0; k < 3; ++k) x[3 * i + k] = p[k];
    }
    EXPECT_EQ(body->setPositions(x.data(), static_cast<int64_t>(x.size())), Status::Ok);
    body->elasticForces(*tasks, &forces);
  }
};

// Pᵀ K_n P = K_m: elevation represents a degree-m field exactly at degree n. At rest (linear
// elasticity, no rotation) and for any per-element rotations, since a rotation acting per node
// commutes with the elevation. Checked for 3 -> 2, 3 -> 1 and 2 -> 1, no constraints.
TEST(DegreeLevelAssembly, StiffnessIsTheGalerkinProductOfTheFineStiffness) {
  for (const bool deformed : {false, true}) {
    for (const std::vector<int>& degrees : {std::vector<int>{3, 2, 1}, std::vector<int>{3, 1}, std::vector<int>{2, 1}}) {
      SCOPED_TRACE(deformed ? "deformed and rotated" : "at rest");
      const DeformedBody sys(degrees[0], deformed);
      DegreeHierarchy h;
      ASSERT_EQ(buildDegreeHierarchy(degrees, sys.body->elementNodes().data(), sys.body->elementCount(),
                                     sys.body->nodeCount(), &h),
                Status::Ok);
      Eigen::MatrixXd fine = denseMatrix(sys.body->stepMatrix());
      for (size_t l = 1; l < h.levels.size(); ++l) {
        DegreeLevelAssembly level;
        level.build(h.levels[l], degrees[0], sys.body->restVolumes().data(), sys.body->elementCount(),
                    sys.body->desc().material.density);
        level.assemble(*sys.tasks, sys.body->elementGradientPairs().data(), 0.0);
        const Eigen::MatrixXd P = denseProlongation(h.prolongations[l - 1]);
        const Eigen::MatrixXd galerkin = P.transpose() * fine * P;
        const Eigen::MatrixXd assembled = denseMatrix(level.matrix());
        EXPECT_LT((assembled - galerkin).norm(), 1e-12 * galerkin.norm())
            << "degrees " << degrees[0] << " -> " << h.levels[l].degree;
        EXPECT_GT(galerkin.norm(), 0.0);
        fine = galerkin;
      }
    }
  }
}

// The mass part is the lumped BB mass of the coarse degree: ρV / C(m+3, 3) per element node,
// scaled by the integrator's mass factor; it carries the body's whole mass at every degree.
TEST(DegreeLevelAssembly, MassIsTheLumpedMassOfTheCoarseDegree) {
  const DeformedBody sys(3, true);
  DegreeHierarchy h;
  ASSERT_EQ(buildDegreeHierarchy({3, 2, 1}, sys.body->elementNodes().data(), sys.body->elementCount(),
                                 sys.body->nodeCount(), &h),
            Status::Ok);
  double bodyMass = 0.0;
  for (double m : sys.body->nodeMasses()) bodyMass += m;
  const std::vector<double> zeroPairs(sys.body->elementGradientPairs().size(), 0.0);
  for (size_t l = 1; l < h.levels.size(); ++l) {
    DegreeLevelAssembly level;
    level.build(h.levels[l], 3, sys.body->restVolumes().data(), sys.body->elementCount(),
                sys.body->desc().material.density);
    level.assemble(*sys.tasks, zeroPairs.data(), 1.5);
    const Eigen::MatrixXd M = denseMatrix(level.matrix());
    EXPECT_NEAR(M.trace() / 3.0, 1.5 * bodyMass, 1e-12 * bodyMass);
    EXPECT_LT((M - Eigen::MatrixXd(M.diagonal().asDiagonal())).norm(), 1e-15 * M.norm()) << "lumped: diagonal";
    double levelMass = 0.0;
    for (double m : level.nodeMasses()) levelMass += m;
    EXPECT_NEAR(levelMass, bodyMass, 1e-12 * bodyMass);
    // Degree 1: every vertex gets a quarter of each of its tets' mass.
    if (level.degree() == 1) {
      std::vector<double> quarter(static_cast<size_t>(h.levels[l].nodeCount), 0.0);
      for (int64_t e = 0; e < sys.body->elementCount(); ++e)
        for (int a = 0; a < 4; ++a)
          quarter[h.levels[l].elementNodes[4 * e + a]] +=
              sys.body->desc().material.density * sys.body->restVolumes()[e] / 4.0;
      for (int32_t i = 0; i < h.levels[l].nodeCount; ++i)
        EXPECT_NEAR(level.nodeMasses()[i], quarter[i], 1e-12 * quarter[i]);
    }
  }
}

}  // namespace
}  // namespace vp
