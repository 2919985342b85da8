#include <cuda_runtime.h>

#include <utility>

#include "device_support.cuh"
#include "gpu_kernels/device_poisson_operator.h"

namespace vp::gpu {
namespace {

constexpr int kThreads = 256;

__global__ void poissonApplyKernel(kernels::PoissonStencil<double> s, const double* x, double* y) {
  const int64_t cell = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  if (cell < s.nx * s.ny * s.nz) y[cell] = kernels::poissonApplyCell(s, cell, x);
}

}  // namespace

struct DevicePoissonOperator::Impl {
  kernels::PoissonStencil<double> stencil;  // device pointers
  DeviceArray<double> cu, cv, cw, diagonal, x, y;

  int64_t cells() const { return stencil.nx * stencil.ny * stencil.nz; }
  void launch() {
    const unsigned blocks = static_cast<unsigned>((cells() + kThreads - 1) / kThreads);
    poissonApplyKernel<<<blocks, kThreads>>>(stencil, x.get(), y.get());
  }
};

DevicePoissonOperator::DevicePoissonOperator(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DevicePoissonOperator::~DevicePoissonOperator() = default;

std::unique_ptr<DevicePoissonOperator> DevicePoissonOperator::create(const kernels::PoissonStencil<double>& host,
                                                                     std::string* error) {
  auto d = std::make_unique<Impl>();
  const size_t nx = static_cast<size_t>(host.nx), ny = static_cast<size_t>(host.ny), nz = static_cast<size_t>(host.nz);
  const size_t cells = nx * ny * nz;
  if (failed(d->cu.upload(host.cu, (nx + 1) * ny * nz), error) || failed(d->cv.upload(host.cv, nx * (ny + 1) * nz), error) ||
      failed(d->cw.upload(host.cw, nx * ny * (nz + 1)), error) || failed(d->diagonal.upload(host.diagonal, cells), error) ||
      failed(d->x.allocate(cells), error) || failed(d->y.allocate(cells), error))
    return nullptr;
  d->stencil = host;
  d->stencil.cu = d->cu.get();
  d->stencil.cv = d->cv.get();
  d->stencil.cw = d->cw.get();
  d->stencil.diagonal = d->diagonal.get();
  d->stencil.span = nullptr;
  return std::unique_ptr<DevicePoissonOperator>(new DevicePoissonOperator(std::move(d)));
}

bool DevicePoissonOperator::apply(const double* x, double* y, std::string* error) {
  Impl& d = *impl_;
  const size_t bytes = static_cast<size_t>(d.cells()) * sizeof(double);
  if (failed(cudaMemcpy(d.x.get(), x, bytes, cudaMemcpyHostToDevice), error)) return false;
  d.launch();
  return !failed(cudaMemcpy(y, d.y.get(), bytes, cudaMemcpyDeviceToHost), error);
}

bool DevicePoissonOperator::timeApply(int repeats, double* msPerApply, std::string* error) {
  Impl& d = *impl_;
  if (failed(cudaMemset(d.x.get(), 0, static_cast<size_t>(d.cells()) * sizeof(double)), error)) return false;
  d.launch();  // warm-up
  EventTimer timer;
  timer.start();
  for (int i = 0; i < repeats; ++i) d.launch();
  const double ms = timer.stopMs();
  if (failed(cudaSuccess, error)) return false;
  *msPerApply = ms / (repeats > 0 ? repeats : 1);
  return true;
}

}  // namespace vp::gpu
