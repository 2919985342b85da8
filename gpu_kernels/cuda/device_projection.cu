#include <cuda_runtime.h>

#include <utility>

#include "device_support.cuh"
#include "gpu_kernels/device_projection.h"
#include "gpu_kernels/pressure_update_kernels.h"

namespace vp::gpu {
namespace {

// b = -(rho h / dt) netOutflow(u*) on fluid cells; non-fluid cells get b = 0 and p = 0 (no
// stale pressure leaks into an open face's gradient).
__global__ void rhsKernel(kernels::NetOutflowFields in, const int32_t* region, double scale, double* b,
                          double* pressure) {
  const kernels::MacLayout& g = in.grid;
  const int64_t c = launch::index();
  if (c >= g.nx * g.ny * g.nz) return;
  const bool fluid = region[c] >= 0;
  b[c] = (fluid ? kernels::netOutflowCell(in, c % g.nx, (c / g.nx) % g.ny, c / (g.nx * g.ny)) : 0.0) * scale;
  if (!fluid) pressure[c] = 0.0;
}

__global__ void updateKernel(kernels::PressureUpdateFields in, kernels::MacLayout g, int a, double* u) {
  const int64_t fx = g.nx + (a == 0), fy = g.ny + (a == 1), fz = g.nz + (a == 2);
  const int64_t f = launch::index();
  if (f < fx * fy * fz) kernels::pressureUpdateFaceAt(in, g, a, f % fx, (f / fx) % fy, f / (fx * fy), u);
}

}  // namespace

struct DeviceProjection::Impl {
  kernels::NetOutflowFields fields{};  // device pointers
  double h = 0.0;
  DeviceArray<double> open[3], solidVelocity[3], velocity[3], liquidPhi;
  DeviceArray<int32_t> region;
  std::unique_ptr<DevicePressureSolver> solver;

  int64_t cells() const { return fields.grid.nx * fields.grid.ny * fields.grid.nz; }
  size_t faces(int a) const {
    const kernels::MacLayout& g = fields.grid;
    return static_cast<size_t>((g.nx + (a == 0)) * (g.ny + (a == 1)) * (g.nz + (a == 2)));
  }
};

DeviceProjection::DeviceProjection(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceProjection::~DeviceProjection() = default;

std::unique_ptr<DeviceProjection> DeviceProjection::create(const ProjectionView& view, std::string* error) {
  auto d = std::make_unique<Impl>();
  d->fields.grid = view.fractions.grid;
  d->h = view.h;
  for (int a = 0; a < 3; ++a) {
    if (failed(d->open[a].upload(view.fractions.open[a], d->faces(a)), error) ||
        failed(d->solidVelocity[a].upload(view.fractions.solidVelocity[a], d->faces(a)), error) ||
        failed(d->velocity[a].allocate(d->faces(a)), error))
      return nullptr;
    d->fields.open[a] = d->open[a].get();
    d->fields.solidVelocity[a] = d->solidVelocity[a].get();
    d->fields.velocity[a] = d->velocity[a].get();
  }
  const size_t cells = static_cast<size_t>(d->cells());
  if (failed(d->region.upload(view.solve.fineRegions.region, cells), error)) return nullptr;
  if (view.liquidPhi && failed(d->liquidPhi.upload(view.liquidPhi, cells), error)) return nullptr;
  d->solver = DevicePressureSolver::create(view.solve, error);
  if (!d->solver) return nullptr;
  return std::unique_ptr<DeviceProjection>(new DeviceProjection(std::move(d)));
}

// As PressureProjectionRun: right-hand side, solve, velocity update.
bool DeviceProjection::project(double* const u[3], double* pressure, double dt, double density, double tolerance,
                               int maxIterations, DevicePressureResult* result, std::string* error) {
  Impl& d = *impl_;
  const size_t cellBytes = static_cast<size_t>(d.cells()) * sizeof(double);
  for (int a = 0; a < 3; ++a)
    if (failed(cudaMemcpy(d.velocity[a].get(), u[a], d.faces(a) * sizeof(double), cudaMemcpyHostToDevice), error))
      return false;
  double* p = d.solver->solution();
  if (failed(cudaMemcpy(p, pressure, cellBytes, cudaMemcpyHostToDevice), error)) return false;
  rhsKernel<<<launch::blocks(d.cells()), launch::kThreads>>>(d.fields, d.region.get(), -density * d.h / dt,
                                                             d.solver->rhs(), p);
  if (!d.solver->solveResident(tolerance, maxIterations, result, error)) return false;
  const kernels::PressureUpdateFields update{nullptr, nullptr, p, d.liquidPhi.get(), dt / (density * d.h)};
  for (int a = 0; a < 3; ++a) {
    kernels::PressureUpdateFields in = update;
    in.open = d.open[a].get();
    in.solidVelocity = d.solidVelocity[a].get();
    updateKernel<<<launch::blocks(static_cast<int64_t>(d.faces(a))), launch::kThreads>>>(in, d.fields.grid, a,
                                                                                         d.velocity[a].get());
  }
  for (int a = 0; a < 3; ++a)
    if (failed(cudaMemcpy(u[a], d.velocity[a].get(), d.faces(a) * sizeof(double), cudaMemcpyDeviceToHost), error))
      return false;
  return !failed(cudaMemcpy(pressure, p, cellBytes, cudaMemcpyDeviceToHost), error);
}

}  // namespace vp::gpu
