// Kernel bodies of the smoke's body forces (runtime/fluid/smoke_forces.h) as functions of one
// cell or face and plain arrays: buoyancy, the cell-centred velocity, vorticity, the
// confinement force, and a cell force's mean on a face.
//
// Cells: index i + nx (j + ny k). Vector fields per cell are 3 doubles, cell c at 3 c.
// Differences are central over the clamped neighbours, so one-sided at the domain's sides and
// 0 along an axis with a single cell.
#pragma once

#include <cmath>
#include <cstdint>

#include "gpu_kernels/cell_lattice.h"
#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

// Offsets of the two cells of the central difference along a at cell coordinate `at`, and
// the distance between their centres (0 with one cell along a).
VP_HOST_DEVICE inline double differenceSpan(const CellLattice& g, int a, int at, int64_t* lo, int64_t* hi) {
  const int below = at - 1 > 0 ? at - 1 : 0;
  const int above = at + 1 < g.n[a] - 1 ? at + 1 : g.n[a] - 1;
  *lo = (below - at) * g.stride[a];
  *hi = (above - at) * g.stride[a];
  return static_cast<double>(above - below) * g.h;
}

// The velocity at the centre of cell (i, j, k) of an nx x ny x nz MAC grid whose face arrays
// are u[0..2] (layouts as in runtime/fluid/solids/face_fraction_field.h): per axis the mean of
// the cell's two faces.
VP_HOST_DEVICE inline void cellVelocityAt(const double* const u[3], int nx, int ny, int i, int j, int k,
                                          double out[3]) {
  const int64_t planeCells = static_cast<int64_t>(nx) * ny;
  const int64_t fu = i + static_cast<int64_t>(nx + 1) * (j + static_cast<int64_t>(ny) * k);
  const int64_t fv = i + static_cast<int64_t>(nx) * (j + static_cast<int64_t>(ny + 1) * k);
  const int64_t fw = i + nx * static_cast<int64_t>(j) + planeCells * k;
  out[0] = 0.5 * (u[0][fu] + u[0][fu + 1]);
  out[1] = 0.5 * (u[1][fv] + u[1][fv + nx]);
  out[2] = 0.5 * (u[2][fw] + u[2][fw + planeCells]);
}

// The Boussinesq buoyancy's component along `up` (a unit vector's component): up (-alpha d +
// beta (T - T_ambient)).
VP_HOST_DEVICE inline double buoyancy(double up, double alpha, double beta, double ambient, double density,
                                      double temperature) {
  return up * (-alpha * density + beta * (temperature - ambient));
}

// |v| of a 3-vector, summed as (x^2 + y^2) + z^2: the order of Eigen's vectorized norm() of a
// Vector3d on x86-64 (SSE2 pairs, then the third), which these kernels replaced bit for bit.
VP_HOST_DEVICE inline double norm3(const double v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// omega from the velocity gradient, gradient[b][a] = d u_b / d x_a.
VP_HOST_DEVICE inline void curlOf(const double gradient[3][3], double omega[3]) {
  omega[0] = gradient[2][1] - gradient[1][2];
  omega[1] = gradient[0][2] - gradient[2][0];
  omega[2] = gradient[1][0] - gradient[0][1];
}

// omega = curl u at cell (i, j, k) from the cell-centred velocities.
VP_HOST_DEVICE inline void vorticityAt(const CellLattice& g, const double* velocity, int i, int j, int k,
                                       double omega[3]) {
  const int at[3] = {i, j, k};
  const int64_t c = i + g.stride[1] * j + g.stride[2] * k;
  double gradient[3][3];
  for (int a = 0; a < 3; ++a) {
    int64_t lo, hi;
    const double span = differenceSpan(g, a, at[a], &lo, &hi);
    for (int b = 0; b < 3; ++b)
      gradient[b][a] = span > 0.0 ? (velocity[3 * (c + hi) + b] - velocity[3 * (c + lo) + b]) / span : 0.0;
  }
  curlOf(gradient, omega);
}

// vorticityAt for a cell with neighbours on both sides along every axis: the differences span
// `twoH` = 2 h, and the values are vorticityAt's bit for bit (the same operations), without
// its per-axis clamps, so a row of such cells is a loop the compiler can vectorize.
VP_HOST_DEVICE inline void interiorVorticityAt(const CellLattice& g, const double* velocity, int64_t c, double twoH,
                                               double omega[3]) {
  double gradient[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      gradient[b][a] = (velocity[3 * (c + g.stride[a]) + b] - velocity[3 * (c - g.stride[a]) + b]) / twoH;
  curlOf(gradient, omega);
}

// Vorticity confinement at cell c from eta = grad|omega| there: epsilon h (N x omega),
// N = eta / |eta|. The small constant keeps N finite where |omega| is flat; such places get no
// force.
VP_HOST_DEVICE inline void confinementFrom(const CellLattice& g, const double* omega, const double eta[3],
                                           double epsilon, int64_t c, double force[3]) {
  const double denominator = norm3(eta) + 1e-12 / g.h;
  const double n[3] = {eta[0] / denominator, eta[1] / denominator, eta[2] / denominator};
  const double* w = omega + 3 * c;
  const double scale = epsilon * g.h;
  force[0] = scale * (n[1] * w[2] - n[2] * w[1]);
  force[1] = scale * (n[2] * w[0] - n[0] * w[2]);
  force[2] = scale * (n[0] * w[1] - n[1] * w[0]);
}

// Vorticity confinement at cell (i, j, k).
VP_HOST_DEVICE inline void confinementAt(const CellLattice& g, const double* omega, const double* omegaNorm,
                                         double epsilon, int i, int j, int k, double force[3]) {
  const int at[3] = {i, j, k};
  const int64_t c = i + g.stride[1] * j + g.stride[2] * k;
  double eta[3];
  for (int a = 0; a < 3; ++a) {
    int64_t lo, hi;
    const double span = differenceSpan(g, a, at[a], &lo, &hi);
    eta[a] = span > 0.0 ? (omegaNorm[c + hi] - omegaNorm[c + lo]) / span : 0.0;
  }
  confinementFrom(g, omega, eta, epsilon, c, force);
}

// confinementAt for a cell with neighbours on both sides along every axis (as
// interiorVorticityAt: the same bits, no clamps).
VP_HOST_DEVICE inline void interiorConfinementAt(const CellLattice& g, const double* omega, const double* omegaNorm,
                                                 double epsilon, int64_t c, double twoH, double force[3]) {
  double eta[3];
  for (int a = 0; a < 3; ++a) eta[a] = (omegaNorm[c + g.stride[a]] - omegaNorm[c - g.stride[a]]) / twoH;
  confinementFrom(g, omega, eta, epsilon, c, force);
}

// A face's velocity after dt of a cell force: the mean of its two cells' values.
VP_HOST_DEVICE inline double faceVelocityAfterForce(double u, double dt, double forceLow, double forceHigh) {
  return u + dt * (0.5 * (forceLow + forceHigh));
}

}  // namespace vp::kernels
