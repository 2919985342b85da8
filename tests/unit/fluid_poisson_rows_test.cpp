// The pressure operator's row kernels (fluid/pressure/poisson_rows.h) against a per-cell
// reference written out from the operator's definition, bit for bit: the kernels peel a row's
// end cells, skip cells outside its span and store with selects, and none of that may change a
// value. Grids as thin as one cell along an axis, odd widths, rows without fluid, non-fluid
// cells inside spans, with and without row spans.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "fluid/pressure/poisson_rows.h"
#include "random_values.h"

namespace vp {
namespace {

using poisson_rows::Stencil;
using poisson_rows::SweepStart;

template <class T>
struct Level {
  PoissonCoefficients<T> op;
  int nx, ny, nz;
  int64_t cell(int i, int j, int k) const { return i + static_cast<int64_t>(nx) * (j + static_cast<int64_t>(ny) * k); }
  int64_t cells() const { return static_cast<int64_t>(nx) * ny * nz; }
};

// Random couplings on faces between two cells (0 on the domain's faces, as the operator
// has them), some closed; a random positive diagonal on fluid cells, 0 on about a fifth of the
// cells and on every cell of row (0, 0) so one row has no fluid at all.
template <class T>
Level<T> randomLevel(int nx, int ny, int nz, bool spans, uint32_t seed) {
  Level<T> l;
  l.nx = nx;
  l.ny = ny;
  l.nz = nz;
  l.op.grid.nx = nx;
  l.op.grid.ny = ny;
  l.op.grid.nz = nz;
  l.op.grid.h = 0.1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int dims[3][3] = {{nx + 1, ny, nz}, {nx, ny + 1, nz}, {nx, ny, nz + 1}};
  for (int a = 0; a < 3; ++a) {
    const int* d = dims[a];
    l.op.coupling[a].assign(static_cast<size_t>(d[0]) * d[1] * d[2], T(0));
    for (int k = 0; k < d[2]; ++k)
      for (int j = 0; j < d[1]; ++j)
        for (int i = 0; i < d[0]; ++i) {
          const int at[3] = {i, j, k};
          const bool inside = at[a] > 0 && at[a] < d[a] - 1;
          const double r = u(rng);
          if (inside && r > 0.15) l.op.coupling[a][i + d[0] * (j + static_cast<size_t>(d[1]) * k)] = T(r);
        }
  }
  l.op.diagonal.assign(static_cast<size_t>(l.cells()), T(0));
  for (int64_t c = 0; c < l.cells(); ++c)
    if (c >= nx && u(rng) > 0.2) l.op.diagonal[static_cast<size_t>(c)] = T(0.5 + 6.0 * u(rng));
  if (spans) {
    l.op.rowSpan.resize(static_cast<size_t>(2 * ny * nz));
    for (int64_t row = 0; row < static_cast<int64_t>(ny) * nz; ++row) {
      int first = 0, last = nx;
      while (first < nx && !(l.op.diagonal[static_cast<size_t>(nx * row + first)] > T(0))) ++first;
      while (last > first && !(l.op.diagonal[static_cast<size_t>(nx * row + last - 1)] > T(0))) --last;
      l.op.rowSpan[static_cast<size_t>(2 * row)] = first;
      l.op.rowSpan[static_cast<size_t>(2 * row + 1)] = last;
    }
  }
  return l;
}

// sum_f A_f x_nb of cell (i, j, k) in the operator's order (-x, +x, -y, +y, -z, +z); a
// neighbour outside the grid counts 0 (its face's coupling is 0 anyway).
template <class T>
T neighbourSum(const Level<T>& l, const T* x, int i, int j, int k) {
  const PoissonCoefficients<T>& op = l.op;
  auto value = [&](int a, int b, int c) {
    return a < 0 || b < 0 || c < 0 || a >= l.nx || b >= l.ny || c >= l.nz ? T(0) : x[l.cell(a, b, c)];
  };
  const size_t u = static_cast<size_t>(i + (l.nx + 1) * (j + static_cast<int64_t>(l.ny) * k));
  const size_t v = static_cast<size_t>(i + l.nx * (j + static_cast<int64_t>(l.ny + 1) * k));
  const size_t w = static_cast<size_t>(l.cell(i, j, k)), planeStride = static_cast<size_t>(l.nx) * l.ny;
  return op.coupling[0][u] * value(i - 1, j, k) + op.coupling[0][u + 1] * value(i + 1, j, k) +
         op.coupling[1][v] * value(i, j - 1, k) + op.coupling[1][v + static_cast<size_t>(l.nx)] * value(i, j + 1, k) +
         op.coupling[2][w] * value(i, j, k - 1) + op.coupling[2][w + planeStride] * value(i, j, k + 1);
}

using testing_values::randomValues;

template <class T>
void expectSameBits(const std::vector<T>& expected, const std::vector<T>& actual, const char* what) {
  ASSERT_EQ(expected.size(), actual.size());
  for (size_t c = 0; c < expected.size(); ++c)
    ASSERT_EQ(std::memcmp(&expected[c], &actual[c], sizeof(T)), 0)
        << what << ": cell " << c << " expected " << expected[c] << " got " << actual[c];
}

template <class Check>
void forEachCase(const Check& check) {
  const int dims[][3] = {{1, 3, 2}, {2, 2, 3}, {3, 1, 1}, {5, 4, 3}, {17, 6, 5}, {600, 2, 2}};
  uint32_t seed = 1;
  for (const auto& d : dims)
    for (bool spans : {false, true}) {
      SCOPED_TRACE(::testing::Message() << d[0] << "x" << d[1] << "x" << d[2] << (spans ? " with spans" : ""));
      check(d[0], d[1], d[2], spans, ++seed);
    }
}

TEST(FluidPoissonRows, OperatorAndResidualRowsEqualTheCellFormulas) {
  forEachCase([](int nx, int ny, int nz, bool spans, uint32_t seed) {
    const Level<double> ld = randomLevel<double>(nx, ny, nz, spans, seed);
    const Level<float> lf = randomLevel<float>(nx, ny, nz, spans, seed);
    const std::vector<double> xd = randomValues<double>(ld.cells(), seed + 100);
    const std::vector<float> xf = randomValues<float>(lf.cells(), seed + 200);
    const std::vector<float> bf = randomValues<float>(lf.cells(), seed + 300);
    std::vector<double> apply(static_cast<size_t>(ld.cells()), 7.0), applyExpected(apply.size());
    std::vector<float> residual(static_cast<size_t>(lf.cells()), 7.0f), residualExpected(residual.size());
    const Stencil<double> sd(ld.op);
    const Stencil<float> sf(lf.op);
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j) {
        poisson_rows::applyRow(sd, j, k, xd.data(), apply.data());
        const size_t rowStart = static_cast<size_t>(nx) * (static_cast<size_t>(j) + static_cast<size_t>(ny) * k);
        poisson_rows::residualRow(sf, j, k, bf.data(), xf.data(), residual.data() + rowStart);
        for (int i = 0; i < nx; ++i) {
          const size_t c = static_cast<size_t>(ld.cell(i, j, k));
          const double d = ld.op.diagonal[c];
          applyExpected[c] = d > 0.0 ? d * xd[c] - neighbourSum(ld, xd.data(), i, j, k) : 0.0;
          const float df = lf.op.diagonal[c];
          residualExpected[c] = df > 0.0f ? bf[c] + neighbourSum(lf, xf.data(), i, j, k) - df * xf[c] : 0.0f;
        }
      }
    expectSameBits(applyExpected, apply, "A x");
    expectSameBits(residualExpected, residual, "b - A x");
  });
}

TEST(FluidPoissonRows, GaussSeidelAndJacobiRowsEqualTheCellFormulas) {
  forEachCase([](int nx, int ny, int nz, bool spans, uint32_t seed) {
    const Level<float> l = randomLevel<float>(nx, ny, nz, spans, seed);
    const Stencil<float> s(l.op);
    const std::vector<float> b = randomValues<float>(l.cells(), seed + 400);
    const std::vector<float> x0 = randomValues<float>(l.cells(), seed + 500);
    auto spanOf = [&](int j, int k, int* first, int* last) {
      const int64_t row = j + static_cast<int64_t>(ny) * k;
      *first = static_cast<int>(s.spanBegin(row));
      *last = static_cast<int>(s.spanEnd(row));
    };
    for (int colour = 0; colour < 2; ++colour)
      for (SweepStart start :
           {SweepStart::Continue, SweepStart::FromZeroFirstColour, SweepStart::FromZeroSecondColour}) {
        SCOPED_TRACE(::testing::Message() << "colour " << colour << " start " << static_cast<int>(start));
        // One half-sweep row by row: each colour cell reads only the other colour, so the
        // reference may read the old values throughout.
        std::vector<float> x = x0, expected = x0;
        for (int k = 0; k < nz; ++k)
          for (int j = 0; j < ny; ++j) {
            poisson_rows::gaussSeidelRow(s, j, k, b.data(), x.data(), colour, start);
            int first, last;
            spanOf(j, k, &first, &last);
            for (int i = 0; i < nx; ++i) {
              const size_t c = static_cast<size_t>(l.cell(i, j, k));
              const float d = l.op.diagonal[c];
              const bool inSpan = i >= first && i < last, mine = ((i + j + k + colour) & 1) == 0;
              if (start == SweepStart::FromZeroFirstColour && !inSpan) expected[c] = 0.0f;
              if (!inSpan || !mine) continue;
              if (start == SweepStart::FromZeroFirstColour) expected[c] = d > 0.0f ? (b[c] + 0.0f) / d : 0.0f;
              else if (d > 0.0f) expected[c] = (b[c] + neighbourSum(l, x0.data(), i, j, k)) / d;
              else if (start == SweepStart::FromZeroSecondColour) expected[c] = 0.0f;
            }
          }
        expectSameBits(expected, x, "Gauss-Seidel");
      }
    const float weight = 6.0f / 7.0f;
    for (bool fromZero : {false, true}) {
      std::vector<float> out(static_cast<size_t>(l.cells()), 7.0f), expected(out.size());
      for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j) {
          poisson_rows::jacobiRow(s, j, k, b.data(), fromZero ? nullptr : x0.data(), out.data(), weight);
          for (int i = 0; i < nx; ++i) {
            const size_t c = static_cast<size_t>(l.cell(i, j, k));
            const float d = l.op.diagonal[c];
            expected[c] = !(d > 0.0f) ? 0.0f
                          : fromZero  ? weight * b[c] / d
                                      : x0[c] + weight * (b[c] + neighbourSum(l, x0.data(), i, j, k) - d * x0[c]) / d;
          }
        }
      expectSameBits(expected, out, fromZero ? "Jacobi from zero" : "Jacobi");
    }
  });
}

}  // namespace
}  // namespace vp
