// Built with --fmad=false (gpu_kernels/CMakeLists.txt): the advection's bits are the CPU's.
#include <cuda_runtime.h>

#include <algorithm>
#include <utility>

#include "device_support.cuh"
#include "gpu_kernels/device_velocity_advection.h"

namespace vp::gpu {
namespace {

constexpr int kThreads = 256;

// Face f of the a-lattice as (i, j, k).
__device__ bool faceOf(const kernels::MacVelocityView& v, int a, int64_t f, int at[3]) {
  const int* d = v.faceDims[a];
  if (f >= static_cast<int64_t>(d[0]) * d[1] * d[2]) return false;
  at[0] = static_cast<int>(f % d[0]);
  at[1] = static_cast<int>((f / d[0]) % d[1]);
  at[2] = static_cast<int>(f / (static_cast<int64_t>(d[0]) * d[1]));
  return true;
}

// The semi-Lagrangian pass of axis a: into out (and, for MacCormack, the stencil's range).
__global__ void forwardKernel(kernels::MacVelocityView v, int a, double dt, double* out, double* lo, double* hi) {
  const int64_t f = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  int at[3];
  if (!faceOf(v, a, f, at)) return;
  out[f] = lo != nullptr ? kernels::advectFace(v, a, at, dt, v.u[a], lo + f, hi + f)
                         : kernels::advectFace(v, a, at, dt, v.u[a]);
}

__global__ void correctionKernel(kernels::MacVelocityView v, int a, double dt, const double* forward,
                                 const double* lo, const double* hi, double* out) {
  const int64_t f = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  int at[3];
  if (faceOf(v, a, f, at)) out[f] = kernels::maccormackFace(v, a, at, f, dt, v.u[a], forward, lo[f], hi[f]);
}

}  // namespace

struct DeviceVelocityAdvection::Impl {
  kernels::MacVelocityView view{};  // device pointers: the current velocity
  DeviceArray<double> u[3], advected[3], forward, lo, hi;

  size_t faces(int a) const {
    return static_cast<size_t>(view.faceDims[a][0]) * view.faceDims[a][1] * view.faceDims[a][2];
  }
  // As advectVelocity: every axis reads the old velocity; the new one is swapped in at the end.
  void advect(double dt, bool maccormack) {
    for (int a = 0; a < 3; ++a) {
      const unsigned blocks = static_cast<unsigned>((faces(a) + kThreads - 1) / kThreads);
      if (!maccormack) {
        forwardKernel<<<blocks, kThreads>>>(view, a, dt, advected[a].get(), nullptr, nullptr);
        continue;
      }
      forwardKernel<<<blocks, kThreads>>>(view, a, dt, forward.get(), lo.get(), hi.get());
      correctionKernel<<<blocks, kThreads>>>(view, a, dt, forward.get(), lo.get(), hi.get(), advected[a].get());
    }
    for (int a = 0; a < 3; ++a) {
      u[a].swap(advected[a]);
      view.u[a] = u[a].get();
    }
  }
};

DeviceVelocityAdvection::DeviceVelocityAdvection(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceVelocityAdvection::~DeviceVelocityAdvection() = default;

std::unique_ptr<DeviceVelocityAdvection> DeviceVelocityAdvection::create(const kernels::MacVelocityView& host,
                                                                         std::string* error) {
  auto d = std::make_unique<Impl>();
  d->view = host;
  size_t largest = 0;
  for (int a = 0; a < 3; ++a) {
    const size_t n = d->faces(a);
    largest = std::max(largest, n);
    if (failed(d->u[a].upload(host.u[a], n), error) || failed(d->advected[a].allocate(n), error)) return nullptr;
    d->view.u[a] = d->u[a].get();
  }
  if (failed(d->forward.allocate(largest), error) || failed(d->lo.allocate(largest), error) ||
      failed(d->hi.allocate(largest), error))
    return nullptr;
  return std::unique_ptr<DeviceVelocityAdvection>(new DeviceVelocityAdvection(std::move(d)));
}

bool DeviceVelocityAdvection::advect(double dt, bool maccormack, std::string* error) {
  impl_->advect(dt, maccormack);
  return !failed(cudaDeviceSynchronize(), error);
}

bool DeviceVelocityAdvection::download(double* const u[3], std::string* error) {
  for (int a = 0; a < 3; ++a)
    if (failed(cudaMemcpy(u[a], impl_->u[a].get(), impl_->faces(a) * sizeof(double), cudaMemcpyDeviceToHost), error))
      return false;
  return true;
}

bool DeviceVelocityAdvection::timeAdvect(int repeats, double dt, bool maccormack, double* msPerAdvect,
                                         std::string* error) {
  const int n = repeats > 0 ? repeats : 1;
  impl_->advect(dt, maccormack);  // warm-up
  EventTimer timer;
  timer.start();
  for (int i = 0; i < n; ++i) impl_->advect(dt, maccormack);
  *msPerAdvect = timer.stopMs() / n;
  return !failed(cudaDeviceSynchronize(), error);
}

}  // namespace vp::gpu
