// Layered velocity extrapolation: exact constant extrapolation across a flat surface, the
// L h |grad u| bound for a linear field around a liquid drop, closed faces on request.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "collide/face_coverage.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/surface/free_surface.h"
#include "fluid/surface/velocity_extrapolation.h"
#include "fluid_liquid_test_util.h"

namespace vp {
namespace {

using testutil::forEachFace;

struct Liquid {
  MacGrid grid;
  FaceFractionField fractions;
  Array<double> phi;
};

template <class Sdf>
void makeSetup(int n, const Sdf& sdf, Liquid* s) {
  const MacGridSpec spec = testutil::unitCubeGrid(n);
  ASSERT_EQ(initMacGrid(spec, testutil::kClosedTank, &s->grid), Status::Ok);
  ASSERT_EQ(initFaceFractionField(spec, &s->fractions), Status::Ok);
  s->phi = testutil::sampleCells(s->grid, sdf);
}

// Known faces get field(a, x); all others a sentinel that must not survive where reached.
template <class Field>
void fillKnown(Liquid& s, const VelocityExtrapolationState& marks, const Field& field) {
  forEachFace(s.grid, [&](int a, int i, int j, int k, size_t f) {
    s.grid.velocity[a][f] = marks.mark[a][f] == 0 ? field(a, s.grid.faceCentre(a, i, j, k)) : 1e6;
  });
}

TEST(FluidVelocityExtrapolation, FlatSurfaceIsConstantAlongTheNormal) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double surface = 0.43;
  Liquid s;
  makeSetup(16, [&](const Eigen::Vector3d& x) { return x.y() - surface; }, &s);
  const int layers = 3;
  VelocityExtrapolationState state;
  // First call only to learn the known faces (0 layers changes nothing).
  ASSERT_EQ(extrapolateVelocity(*tasks, s.grid, s.fractions, s.phi.data(), {0, false}, state), Status::Ok);
  auto field = [](int a, const Eigen::Vector3d& x) { return 0.3 + a - 1.7 * x.x() + 2.3 * x.y() + 0.9 * x.z(); };
  fillKnown(s, state, field);
  ASSERT_EQ(extrapolateVelocity(*tasks, s.grid, s.fractions, s.phi.data(), {layers, false}, state), Status::Ok);
  const double h = s.grid.spec.h;
  // Liquid rows j <= 6 (centre 6.5 h = 0.406 < 0.43). The highest known face of each axis:
  // v-faces up to y = 7 h (the liquid-air face), u- and w-faces in the top liquid row (6.5 h).
  const double topKnown[3] = {6.5 * h, 7.0 * h, 6.5 * h};
  int64_t checked = 0;
  forEachFace(s.grid, [&](int a, int i, int j, int k, size_t f) {
    const uint8_t m = state.mark[a][f];
    const Eigen::Vector3d x = s.grid.faceCentre(a, i, j, k);
    if (m == kExtrapolationFixed) {
      EXPECT_TRUE(s.grid.isWallFace(a, i, j, k));
      return;
    }
    const int layer = static_cast<int>(std::lround((x.y() - topKnown[a]) / h));
    if (layer <= 0) {
      EXPECT_EQ(m, 0);
      return;
    }
    if (layer > layers) {
      EXPECT_EQ(m, kExtrapolationUnreached);
      EXPECT_EQ(s.grid.velocity[a][f], 1e6);
      return;
    }
    EXPECT_EQ(m, layer);
    Eigen::Vector3d below = x;
    below.y() = topKnown[a];
    // Only the face below is of an earlier layer: a plain copy, exact to round-off.
    EXPECT_NEAR(s.grid.velocity[a][f], field(a, below), 1e-12);
    ++checked;
  });
  EXPECT_GT(checked, 3 * 3 * 16 * 15);
}

TEST(FluidVelocityExtrapolation, LinearFieldAroundDropWithinLayerBound) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const Eigen::Vector3d centre(0.52, 0.47, 0.5);
  Liquid s;
  makeSetup(24, [&](const Eigen::Vector3d& x) { return (x - centre).norm() - 0.25; }, &s);
  const int layers = 4;
  VelocityExtrapolationState state;
  ASSERT_EQ(extrapolateVelocity(*tasks, s.grid, s.fractions, s.phi.data(), {0, false}, state), Status::Ok);
  const Eigen::Vector3d gradient(-1.7, 2.3, 0.9);
  auto field = [&](int a, const Eigen::Vector3d& x) { return 0.3 + a + gradient.dot(x); };
  fillKnown(s, state, field);
  ASSERT_EQ(extrapolateVelocity(*tasks, s.grid, s.fractions, s.phi.data(), {layers, false}, state), Status::Ok);
  const double h = s.grid.spec.h, maxSlope = gradient.cwiseAbs().maxCoeff();
  double worstRatio = 0.0, knownMin = 1e9, knownMax = -1e9, extrapolatedMin = 1e9, extrapolatedMax = -1e9;
  int64_t perLayer[8] = {};
  forEachFace(s.grid, [&](int a, int i, int j, int k, size_t f) {
    const uint8_t m = state.mark[a][f];
    const double u = s.grid.velocity[a][f] - a;  // compare components on one scale
    if (m == 0) {
      knownMin = std::min(knownMin, u);
      knownMax = std::max(knownMax, u);
    }
    if (m == 0 || m > layers) return;
    ++perLayer[m];
    extrapolatedMin = std::min(extrapolatedMin, u);
    extrapolatedMax = std::max(extrapolatedMax, u);
    const double error = std::fabs(s.grid.velocity[a][f] - field(a, s.grid.faceCentre(a, i, j, k)));
    worstRatio = std::max(worstRatio, error / (m * h * maxSlope));
  });
  std::printf("    faces per layer 1..4: %lld %lld %lld %lld; worst error / (L h max|g_i|) = %.3f\n",
              static_cast<long long>(perLayer[1]), static_cast<long long>(perLayer[2]),
              static_cast<long long>(perLayer[3]), static_cast<long long>(perLayer[4]), worstRatio);
  for (int l = 1; l <= layers; ++l) EXPECT_GT(perLayer[l], 100);
  EXPECT_LE(worstRatio, 1.0 + 1e-12);
  // Means of known values: no overshoot beyond the known range.
  EXPECT_GE(extrapolatedMin, knownMin - 1e-12);
  EXPECT_LE(extrapolatedMax, knownMax + 1e-12);
}

TEST(FluidVelocityExtrapolation, ClosedFacesOnlyOnRequest) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  Liquid s;
  makeSetup(12, [](const Eigen::Vector3d& x) { return x.y() - 0.7; }, &s);
  ColliderShape box;
  box.kind = ShapeKind::Box;
  box.halfExtents = Eigen::Vector3d(0.2, 0.15, 0.2);
  box.rotation = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  box.translation = Eigen::Vector3d(0.5, 0.35, 0.5);
  PreparedCollider collider;
  ASSERT_EQ(prepareCollider(box, &collider), Status::Ok);
  const PreparedCollider* list[] = {&collider};
  ASSERT_EQ(computeFaceFractions(list, 1, &s.fractions), Status::Ok);
  const double value = 0.625;
  for (int pass = 0; pass < 2; ++pass) {
    const bool intoClosed = pass == 1;
    VelocityExtrapolationState state;
    for (int a = 0; a < 3; ++a) {
      s.grid.velocity[a].assign(s.grid.velocity[a].size(), -3.0);  // "solid" value everywhere
    }
    ASSERT_EQ(extrapolateVelocity(*tasks, s.grid, s.fractions, s.phi.data(), {0, intoClosed}, state), Status::Ok);
    for (int a = 0; a < 3; ++a)
      for (size_t f = 0; f < state.mark[a].size(); ++f)
        if (state.mark[a][f] == 0) s.grid.velocity[a][f] = value;
    ASSERT_EQ(extrapolateVelocity(*tasks, s.grid, s.fractions, s.phi.data(), {3, intoClosed}, state), Status::Ok);
    int64_t closedChanged = 0, closedKept = 0;
    forEachFace(s.grid, [&](int a, int i, int j, int k, size_t f) {
      if (s.grid.isWallFace(a, i, j, k) || effectiveOpenFraction(s.grid, s.fractions, a, i, j, k) > 0.0) return;
      if (s.grid.velocity[a][f] == value) ++closedChanged;
      else if (s.grid.velocity[a][f] == -3.0) ++closedKept;
    });
    if (intoClosed) {
      EXPECT_GT(closedChanged, 10);  // a constant is reproduced exactly
    } else {
      EXPECT_EQ(closedChanged, 0);
      EXPECT_GT(closedKept, 10);
    }
  }
  VelocityExtrapolationState state;
  EXPECT_EQ(extrapolateVelocity(*tasks, s.grid, s.fractions, nullptr, {}, state), Status::InvalidArgument);
  EXPECT_EQ(extrapolateVelocity(*tasks, s.grid, s.fractions, s.phi.data(), {251, false}, state),
            Status::InvalidArgument);
}

}  // namespace
}  // namespace vp
