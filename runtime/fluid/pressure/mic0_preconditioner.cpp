// MIC(0) factorization and triangular solves (see mic0_preconditioner.h).
#include "fluid/pressure/mic0_preconditioner.h"

#include <cmath>

namespace vp {

Status buildMic0Preconditioner(const CutCellPoisson& op, const Mic0Settings& settings,
                               Mic0Preconditioner* preconditioner) {
  if (preconditioner == nullptr) return fail(Status::InvalidArgument, "mic0: preconditioner is null");
  if (!(settings.tuning >= 0.0 && settings.tuning <= 1.0))
    return fail(Status::InvalidArgument, "mic0: tuning %g must lie in [0, 1]", settings.tuning);
  if (!(settings.safety >= 0.0 && settings.safety < 1.0))
    return fail(Status::InvalidArgument, "mic0: safety %g must lie in [0, 1)", settings.safety);
  const MacGridSpec& g = op.grid;
  const int64_t nx = g.nx, ny = g.ny, nz = g.nz;
  const int64_t sy = nx, sz = nx * ny;
  Array<double>& precon = preconditioner->inverseSqrtPivot;
  precon.assign(static_cast<size_t>(nx * ny * nz), 0.0);
  const double* cu = op.coupling[0].data();
  const double* cv = op.coupling[1].data();
  const double* cw = op.coupling[2].data();
  // Couplings of cell c towards +x, +y, +z (0 at the grid's high boundary).
  auto plusX = [&](int64_t i, int64_t j, int64_t k) { return cu[(i + 1) + (nx + 1) * (j + ny * k)]; };
  auto plusY = [&](int64_t i, int64_t j, int64_t k) { return cv[i + nx * ((j + 1) + (ny + 1) * k)]; };
  auto plusZ = [&](int64_t i, int64_t j, int64_t k) { return cw[i + nx * (j + ny * (k + 1))]; };
  for (int64_t k = 0; k < nz; ++k)
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i) {
        const int64_t c = i + nx * (j + ny * k);
        if (op.region[static_cast<size_t>(c)] < 0) continue;
        const double diag = op.diagonal[static_cast<size_t>(c)];
        double e = diag;
        if (i > 0) {
          const double a = plusX(i - 1, j, k), p = precon[c - 1];
          e -= a * a * p * p + settings.tuning * a * (plusY(i - 1, j, k) + plusZ(i - 1, j, k)) * p * p;
        }
        if (j > 0) {
          const double a = plusY(i, j - 1, k), p = precon[c - sy];
          e -= a * a * p * p + settings.tuning * a * (plusX(i, j - 1, k) + plusZ(i, j - 1, k)) * p * p;
        }
        if (k > 0) {
          const double a = plusZ(i, j, k - 1), p = precon[c - sz];
          e -= a * a * p * p + settings.tuning * a * (plusX(i, j, k - 1) + plusY(i, j, k - 1)) * p * p;
        }
        // Modified IC can drive pivots to ~0 (exactly 0 on the last cell of a floating region,
        // whose row sums are 0); the safety falls back to the unmodified diagonal there.
        if (e < settings.safety * diag) e = diag;
        precon[c] = 1.0 / std::sqrt(e);
      }
  return Status::Ok;
}

void applyMic0Preconditioner(const CutCellPoisson& op, const Mic0Preconditioner& preconditioner,
                             const double* r, double* z) {
  const MacGridSpec& g = op.grid;
  const int64_t nx = g.nx, ny = g.ny, nz = g.nz;
  const int64_t sy = nx, sz = nx * ny;
  const double* precon = preconditioner.inverseSqrtPivot.data();
  const double* cu = op.coupling[0].data();
  const double* cv = op.coupling[1].data();
  const double* cw = op.coupling[2].data();
  // Forward: L q = r (q stored in z). L's off-diagonals are -coupling * precon of the lower
  // neighbour.
  for (int64_t k = 0; k < nz; ++k)
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i) {
        const int64_t c = i + nx * (j + ny * k);
        if (precon[c] == 0.0) {
          z[c] = 0.0;
          continue;
        }
        double t = r[c];
        if (i > 0) t += cu[i + (nx + 1) * (j + ny * k)] * precon[c - 1] * z[c - 1];
        if (j > 0) t += cv[i + nx * (j + (ny + 1) * k)] * precon[c - sy] * z[c - sy];
        if (k > 0) t += cw[c] * precon[c - sz] * z[c - sz];
        z[c] = t * precon[c];
      }
  // Backward: L^T z = q, in place (z[c] still holds q[c] when cell c is reached).
  for (int64_t k = nz - 1; k >= 0; --k)
    for (int64_t j = ny - 1; j >= 0; --j)
      for (int64_t i = nx - 1; i >= 0; --i) {
        const int64_t c = i + nx * (j + ny * k);
        if (precon[c] == 0.0) continue;
        double t = z[c];
        if (i + 1 < nx) t += cu[(i + 1) + (nx + 1) * (j + ny * k)] * precon[c] * z[c + 1];
        if (j + 1 < ny) t += cv[i + nx * ((j + 1) + (ny + 1) * k)] * precon[c] * z[c + sy];
        if (k + 1 < nz) t += cw[c + sz] * precon[c] * z[c + sz];
        z[c] = t * precon[c];
      }
}

}  // namespace vp
