// The CPU's batched advection (advection_rows.h) runs the per-sample kernel bodies of
// gpu_kernels/advection_kernels.h stage by stage, with the same bits as the composed
// per-sample kernels: the batch stages equal the kernels applied one sample at a time, and a whole
// semi-Lagrangian advection equals, face by face and cell by cell, the old field sampled at
// the kernel's back-trace. Random velocities (several cells per step, so traces leave the
// domain and get clamped) on a box that is not a cube and not at the origin.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "fluid/advection/advection.h"
#include "fluid/advection/advection_rows.h"
#include "fluid/advection/grid_sampling.h"
#include "gpu_kernels/scalar_advection_kernels.h"

namespace vp {
namespace {

MacGrid randomGrid(uint64_t seed) {
  MacGridSpec spec;
  spec.origin = Vec3(0.1, -0.2, 0.3);
  spec.h = 0.125;
  spec.nx = 70;  // more than one batch per row
  spec.ny = 5;
  spec.nz = 4;
  MacGrid g;
  EXPECT_EQ(initMacGrid(spec, {}, &g), Status::Ok);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> speed(-2.0, 2.0);
  for (int a = 0; a < 3; ++a)
    for (double& u : g.velocity[a]) u = speed(rng);
  return g;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Lattice dims of a-faces (3: cells).
Eigen::Vector3i latticeOf(const MacGrid& g, int a) {
  return a < 3 ? g.faceDims(a) : Eigen::Vector3i(g.spec.nx, g.spec.ny, g.spec.nz);
}

TEST(FluidAdvectionRows, BatchedTracesAndSamplesEqualThePerSampleKernels) {
  const MacGrid g = randomGrid(7);
  const kernels::MacVelocityView v = macVelocityView(g);
  std::mt19937_64 rng(11);
  for (int a = 0; a <= 3; ++a) {
    const Eigen::Vector3i d = latticeOf(g, a);
    const int dims[3] = {d.x(), d.y(), d.z()};
    for (double dt : {0.05, 0.4, -0.3}) {
      TraceStarts starts;
      starts.axis = a;
      starts.j = static_cast<int>(rng() % d.y());
      starts.k = static_cast<int>(rng() % d.z());
      starts.count = 0;
      for (int i = 0; i < d.x() && starts.count < kTraceBatch; ++i)
        if (rng() % 4 != 0) starts.i[starts.count++] = i;  // gaps, as skipped samples leave
      fillTraceStarts(v, &starts);
      PointBatch traced;
      traceBatch(v, starts, dt, a, &traced);
      Array<double> field(static_cast<size_t>(d.prod()));
      for (double& x : field) x = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
      double value[kTraceBatch], lo[kTraceBatch], hi[kTraceBatch], plain[kTraceBatch];
      sampleAtPoints(field.data(), dims, traced, value, lo, hi);
      sampleAtPoints(field.data(), dims, traced, plain);
      ASSERT_GT(starts.count, 10);
      for (int s = 0; s < starts.count; ++s) {
        const int at[3] = {starts.i[s], starts.j, starts.k};
        double x[3], u0[3], g3[3];
        kernels::sampleCentre(v, a, at, x);
        kernels::velocityAtSample(v, a, at, u0);
        kernels::traceToLattice(v, x, u0, dt, a, g3);
        for (int e = 0; e < 3; ++e) {
          ASSERT_TRUE(sameBits(starts.x.at[e][s], x[e])) << "axis " << a << " sample " << s;
          ASSERT_TRUE(sameBits(starts.u0.at[e][s], u0[e])) << "axis " << a << " sample " << s;
          ASSERT_TRUE(sameBits(traced.at[e][s], g3[e])) << "axis " << a << " sample " << s << " dt " << dt;
        }
        int base[3];
        double w[3];
        int64_t index = 0;
        const kernels::LatticeSteps st = kernels::latticeSteps(dims);
        for (int e = 0; e < 3; ++e) {
          kernels::latticeSpan(g3[e], dims[e], &base[e], &w[e]);
          index += base[e] * st.stride[e];
        }
        double l, h;
        const double expected = kernels::trilinear(field.data() + index, st.step, w[0], w[1], w[2], &l, &h);
        ASSERT_TRUE(sameBits(value[s], expected));
        ASSERT_TRUE(sameBits(plain[s], expected));
        ASSERT_TRUE(sameBits(lo[s], l) && sameBits(hi[s], h));
        ASSERT_LE(l, value[s]);
        ASSERT_GE(h, value[s]);
      }
    }
  }
}

// Sampling through open faces: a batch gives connectedTrilinearSample's value and range at
// every point, on masks where some blocks are open (the fast path) and some cut.
TEST(FluidAdvectionRows, BatchedOpenFaceSamplesEqualThePerSampleOnes) {
  const int dims[3] = {9, 6, 5};
  const Eigen::Vector3i lattice(dims[0], dims[1], dims[2]);
  const size_t cells = static_cast<size_t>(lattice.prod());
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Array<double> values(cells);
  Array<uint8_t> faces(cells), blockOpen(cells);
  for (size_t c = 0; c < cells; ++c) {
    values[c] = unit(rng);
    faces[c] = rng() % 5 == 0 ? 0 : static_cast<uint8_t>((rng() & 63) | kCellIsFluid);
    blockOpen[c] = rng() % 2;
  }
  PointBatch at;
  at.count = kTraceBatch;
  for (int s = 0; s < kTraceBatch; ++s)
    for (int d = 0; d < 3; ++d) at.at[d][s] = -1.0 + (dims[d] + 1.0) * unit(rng);  // some outside
  double value[kTraceBatch], lo[kTraceBatch], hi[kTraceBatch], plain[kTraceBatch];
  sampleConnectedAtPoints(values.data(), dims, at, faces.data(), blockOpen.data(), value, lo, hi);
  sampleConnectedAtPoints(values.data(), dims, at, faces.data(), blockOpen.data(), plain, nullptr, nullptr);
  int cut = 0;
  for (int s = 0; s < kTraceBatch; ++s) {
    const Eigen::Vector3d g(at.at[0][s], at.at[1][s], at.at[2][s]);
    SampleRange range;
    const double expected = connectedTrilinearSample(values.data(), lattice, g, faces.data(), blockOpen.data(), &range);
    cut += blockOpen[trilinearStencil(lattice, g).base] == 0;
    ASSERT_TRUE(sameBits(value[s], expected)) << s;
    ASSERT_TRUE(sameBits(plain[s], expected)) << s;
    ASSERT_TRUE(sameBits(lo[s], range.lo) && sameBits(hi[s], range.hi)) << s;
  }
  EXPECT_GT(cut, 10);
  EXPECT_LT(cut, kTraceBatch - 10);
}

// The per-sample reference: the old field (lattice of a-faces, 3: cells) at the back-trace of
// sample `at`.
double semiLagrangianSample(const MacGrid& g, const double* old, int a, const int at[3], double dt) {
  const kernels::MacVelocityView v = macVelocityView(g);
  const Eigen::Vector3i d = latticeOf(g, a);
  const int dims[3] = {d.x(), d.y(), d.z()};
  double x[3], u0[3], from[3];
  kernels::sampleCentre(v, a, at, x);
  kernels::velocityAtSample(v, a, at, u0);
  kernels::traceToLattice(v, x, u0, dt, a, from);
  return kernels::sampleLattice(old, dims, from);
}

TEST(FluidAdvectionRows, SemiLagrangianAdvectionEqualsTheKernelSampleBySample) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double dt = 0.2;
  const MacGrid old = randomGrid(3);
  MacGrid advected = old;
  AdvectionWorkspace work;
  advectVelocity(*tasks, advected, dt, AdvectionScheme::SemiLagrangian, work);
  Array<double> scalar(static_cast<size_t>(old.cellCount()));
  std::mt19937_64 rng(5);
  for (double& x : scalar) x = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
  Array<double> scalarAdvected = scalar;
  Array<double>* fields[1] = {&scalarAdvected};
  advectCellScalars(*tasks, old, dt, AdvectionScheme::SemiLagrangian, fields, 1, work);
  for (int a = 0; a <= 3; ++a) {
    const Eigen::Vector3i d = latticeOf(old, a);
    const double* before = a < 3 ? old.velocity[a].data() : scalar.data();
    const double* after = a < 3 ? advected.velocity[a].data() : scalarAdvected.data();
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const int at[3] = {i, j, k};
          const size_t index = static_cast<size_t>(i + d.x() * (j + d.y() * k));
          ASSERT_TRUE(sameBits(after[index], semiLagrangianSample(old, before, a, at, dt)))
              << "lattice " << a << " at " << i << " " << j << " " << k;
        }
  }
}

// Velocity advection as a device thread runs it, one face at a time: the semi-Lagrangian value
// (kernels::advectFace) and MacCormack's (kernels::maccormackFace over the forward field and
// its ranges) equal advectVelocity's, bit for bit, on every face of every axis.
TEST(FluidAdvectionRows, VelocityAdvectionEqualsThePerFaceKernels) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double dt = 0.2;
  const MacGrid old = randomGrid(9);
  const kernels::MacVelocityView v = macVelocityView(old);
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack}) {
    MacGrid advected = old;
    AdvectionWorkspace work;
    advectVelocity(*tasks, advected, dt, scheme, work);
    int limited = 0, corrected = 0;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3i d = old.faceDims(a);
      const size_t faces = static_cast<size_t>(d.prod());
      std::vector<double> forward(faces), lo(faces), hi(faces);
      auto forEachFace = [&](const auto& body) {
        for (int k = 0; k < d.z(); ++k)
          for (int j = 0; j < d.y(); ++j)
            for (int i = 0; i < d.x(); ++i) {
              const int at[3] = {i, j, k};
              body(at, static_cast<int64_t>(i + d.x() * (j + d.y() * k)));
            }
      };
      forEachFace([&](const int* at, int64_t f) {
        forward[size_t(f)] = kernels::advectFace(v, a, at, dt, old.velocity[a].data(), &lo[size_t(f)], &hi[size_t(f)]);
      });
      forEachFace([&](const int* at, int64_t f) {
        double expected = forward[size_t(f)];
        if (scheme == AdvectionScheme::MacCormack) {
          expected = kernels::maccormackFace(v, a, at, f, dt, old.velocity[a].data(), forward.data(), lo[size_t(f)],
                                             hi[size_t(f)]);
          limited += sameBits(expected, forward[size_t(f)]);
          corrected += !sameBits(expected, forward[size_t(f)]);
        }
        ASSERT_TRUE(sameBits(advected.velocity[a][size_t(f)], expected)) << "axis " << a << " face " << f;
      });
    }
    // Both of MacCormack's outcomes occur (the limiter keeps the forward value on some faces).
    if (scheme == AdvectionScheme::MacCormack) {
      EXPECT_GT(limited, 0);
      EXPECT_GT(corrected, 0);
    }
  }
}

// Scalar advection as a device thread runs it, one cell at a time (gpu_kernels/
// scalar_advection_kernels.h): traces, the forward and MacCormack values under the cell rules,
// and the conserved field's rescale from row sums and the open sides' outflow, equal
// advectCellScalars' bit for bit, with and without open-face masks (some cells solid), for both
// schemes, on a grid with two Open sides.
TEST(FluidAdvectionRows, ScalarAdvectionEqualsThePerCellKernels) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double dt = 0.2;
  MacGrid old = randomGrid(13);
  old.sides[1] = old.sides[3] = DomainSide::Open;
  FaceFractionField fractions;
  ASSERT_EQ(initFaceFractionField(old.spec, &fractions), Status::Ok);
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int a = 0; a < 3; ++a)
    for (double& f : fractions.open[a]) f = rng() % 3 == 0 ? 0.0 : unit(rng);
  CellOpenFaces masks;
  buildCellOpenFaces(*tasks, old, fractions, &masks);
  const size_t cells = static_cast<size_t>(old.cellCount());
  std::vector<Array<double>> start(2, Array<double>(cells));
  for (Array<double>& field : start)
    for (double& x : field) x = unit(rng);
  const double solidValues[2] = {0.0, 0.3};
  const kernels::MacVelocityView v = macVelocityView(old);
  const kernels::MacLayout layout = old.layout();
  const double* const velocity[3] = {old.velocity[0].data(), old.velocity[1].data(), old.velocity[2].data()};
  const int64_t rows = static_cast<int64_t>(old.spec.ny) * old.spec.nz;
  auto total = [&](const double* values) {
    double sum = 0.0;
    for (int64_t row = 0; row < rows; ++row) sum += kernels::cellRowSum(values, old.spec.nx, row);
    return sum;
  };
  int solid = 0;
  for (size_t c = 0; c < cells; ++c) solid += !(masks.faces[c] & kCellIsFluid);
  ASSERT_GT(solid, 0);
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack})
    for (const CellOpenFaces* openFaces : {static_cast<const CellOpenFaces*>(nullptr), &std::as_const(masks)}) {
      SCOPED_TRACE(std::string(scheme == AdvectionScheme::MacCormack ? "MacCormack" : "semi-Lagrangian") +
                   (openFaces ? ", open-face masks" : ""));
      std::vector<Array<double>> advected = start;
      Array<double>* fields[2] = {&advected[0], &advected[1]};
      AdvectionWorkspace work;
      advectCellScalars(*tasks, old, dt, scheme, fields, 2, work, openFaces, solidValues, 0.0, 0);
      const double target = total(start[0].data()) - kernels::openSideOutflow(layout, velocity, start[0].data(), dt,
                                                                              old.spec.h);
      for (int field = 0; field < 2; ++field) {
        kernels::ScalarCellRules rules{openFaces ? masks.faces.data() : nullptr,
                                       openFaces ? masks.blockOpen.data() : nullptr,
                                       nullptr,
                                       &solidValues[field],
                                       {old.spec.nx, old.spec.ny, old.spec.nz}};
        const double* before = start[static_cast<size_t>(field)].data();
        std::vector<double> forward(cells), lo(cells), hi(cells), expected(cells);
        const bool maccormack = scheme == AdvectionScheme::MacCormack;
        for (int64_t c = 0; c < static_cast<int64_t>(cells); ++c) {
          const int at[3] = {static_cast<int>(c % old.spec.nx), static_cast<int>(c / old.spec.nx % old.spec.ny),
                             static_cast<int>(c / old.spec.nx / old.spec.ny)};
          double back[3];
          kernels::traceCell(v, at, dt, back);
          kernels::scalarForwardCell(rules, before, c, back, forward.data(), maccormack ? lo.data() : nullptr,
                                     maccormack ? hi.data() : nullptr);
        }
        for (int64_t c = 0; c < static_cast<int64_t>(cells); ++c) {
          const int at[3] = {static_cast<int>(c % old.spec.nx), static_cast<int>(c / old.spec.nx % old.spec.ny),
                             static_cast<int>(c / old.spec.nx / old.spec.ny)};
          double back[3], ahead[3];
          kernels::traceCell(v, at, dt, back);
          kernels::reflectThrough(at, back, ahead);
          expected[size_t(c)] = maccormack ? kernels::scalarCorrectionCell(rules, before, forward.data(), c, ahead,
                                                                           lo[size_t(c)], hi[size_t(c)])
                                           : forward[size_t(c)];
        }
        if (field == 0) {
          const double scale = kernels::conservationScale(target, total(expected.data()));
          EXPECT_NE(scale, 1.0);
          for (double& x : expected) x *= scale;
        }
        for (size_t c = 0; c < cells; ++c)
          ASSERT_TRUE(sameBits(advected[size_t(field)][c], expected[c])) << "field " << field << " cell " << c;
      }
    }
}

}  // namespace
}  // namespace vp
