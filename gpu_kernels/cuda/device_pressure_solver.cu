#include <cuda_runtime.h>

#include <cmath>
#include <cub/block/block_reduce.cuh>
#include <utility>

#include "device_poisson_multigrid.cuh"
#include "device_support.cuh"
#include "gpu_kernels/device_pressure_solver.h"
#include "gpu_kernels/vector_kernels.h"

namespace vp::gpu {
namespace {

using BlockReduce = cub::BlockReduce<double, launch::kThreads>;

__device__ void addBlockSum(double value, double* target) {
  __shared__ typename BlockReduce::TempStorage storage;
  const double sum = BlockReduce(storage).Sum(value);
  if (threadIdx.x == 0) atomicAdd(target, sum);
}

__global__ void applyKernel(kernels::PoissonStencil<double> s, const double* x, double* y) {
  const int64_t c = launch::index();
  if (c < s.nx * s.ny * s.nz) y[c] = kernels::poissonApplyCell(s, c, x);
}

__global__ void dotKernel(int64_t n, const double* a, const double* b, double* target) {
  const int64_t i = launch::index();
  addBlockSum(i < n ? a[i] * b[i] : 0.0, target);
}

// x += alpha p, r -= alpha q, and r . r.
__global__ void cgStepKernel(int64_t n, double alpha, const double* p, const double* q, double* x, double* r,
                             double* rr) {
  const int64_t i = launch::index();
  addBlockSum(i < n ? kernels::cgStepRange(i, i + 1, alpha, p, q, x, r) : 0.0, rr);
}

// r = b - q
__global__ void residualKernel(int64_t n, const double* b, const double* q, double* r) {
  const int64_t i = launch::index();
  if (i < n) r[i] = b[i] - q[i];
}

__global__ void subtractKernel(int64_t n, const double* v, double* x) {
  const int64_t i = launch::index();
  if (i < n) x[i] -= v[i];
}

__global__ void xpbyKernel(int64_t n, const double* x, double b, double* y) {
  const int64_t i = launch::index();
  if (i < n) kernels::xpbyItem(i, x, b, y);
}

}  // namespace

struct DevicePressureSolver::Impl {
  kernels::PoissonStencil<double> op{};  // device pointers
  DeviceArray<double> cu, cv, cw, diagonal;
  DeviceArray<double> b, x, r, z, p, q, scalars;
  DeviceRegionFilter filter;
  DeviceMultigrid multigrid;
  cudaStream_t stream = nullptr;

  ~Impl() {
    if (stream) cudaStreamDestroy(stream);
  }
  int64_t cells() const { return op.nx * op.ny * op.nz; }
  size_t bytes() const { return static_cast<size_t>(cells()) * sizeof(double); }

  void apply(const double* in, double* out) {
    applyKernel<<<launch::blocks(cells()), launch::kThreads, 0, stream>>>(op, in, out);
  }
  // a . b, read back (the host decides the CG's next step from it).
  bool dot(const double* a, const double* bv, double* out, std::string* error) {
    cudaMemsetAsync(scalars.get(), 0, sizeof(double), stream);
    dotKernel<<<launch::blocks(cells()), launch::kThreads, 0, stream>>>(cells(), a, bv, scalars.get());
    return !failed(cudaMemcpyAsync(out, scalars.get(), sizeof(double), cudaMemcpyDeviceToHost, stream), error) &&
           !failed(cudaStreamSynchronize(stream), error);
  }
  bool cgStep(double alpha, double* rr, std::string* error) {
    cudaMemsetAsync(scalars.get(), 0, sizeof(double), stream);
    cgStepKernel<<<launch::blocks(cells()), launch::kThreads, 0, stream>>>(cells(), alpha, p.get(), q.get(), x.get(),
                                                                           r.get(), scalars.get());
    return !failed(cudaMemcpyAsync(rr, scalars.get(), sizeof(double), cudaMemcpyDeviceToHost, stream), error) &&
           !failed(cudaStreamSynchronize(stream), error);
  }
  // x -= filter(x): what the filter removes stays, as the CPU's CG does when b vanishes.
  void removeFreePart() {
    cudaMemcpyAsync(z.get(), x.get(), bytes(), cudaMemcpyDeviceToDevice, stream);
    filter.apply(z.get(), stream);
    subtractKernel<<<launch::blocks(cells()), launch::kThreads, 0, stream>>>(cells(), z.get(), x.get());
  }
  // z = filter(M r)
  void precondition() {
    multigrid.launch(stream);
    filter.apply(z.get(), stream);
  }
  bool solve(double tolerance, int maxIterations, DevicePressureResult* result, std::string* error);
};

// The CPU's ConjugateGradientRun (linalg/conjugate_gradient.cpp) from the guess in x.
bool DevicePressureSolver::Impl::solve(double tolerance, int maxIterations, DevicePressureResult* result,
                                       std::string* error) {
  *result = DevicePressureResult{};
  // |filtered b| is the scale the tolerance is relative to.
  cudaMemcpyAsync(z.get(), b.get(), bytes(), cudaMemcpyDeviceToDevice, stream);
  filter.apply(z.get(), stream);
  double bb = 0.0;
  if (!dot(z.get(), z.get(), &bb, error)) return false;
  const double bNorm = std::sqrt(bb);
  apply(x.get(), q.get());
  residualKernel<<<launch::blocks(cells()), launch::kThreads, 0, stream>>>(cells(), b.get(), q.get(), r.get());
  filter.apply(r.get(), stream);
  double rr = 0.0;
  if (!dot(r.get(), r.get(), &rr, error)) return false;
  if (bNorm == 0.0) {
    // Nothing drives the system: x = 0 in the free subspace is the exact answer.
    if (rr != 0.0) removeFreePart();
    result->converged = true;
    return true;
  }
  result->relativeResidual = std::sqrt(rr) / bNorm;
  if (result->relativeResidual <= tolerance) {
    result->converged = true;
    return true;
  }
  if (maxIterations <= 0) return true;
  precondition();
  cudaMemcpyAsync(p.get(), z.get(), bytes(), cudaMemcpyDeviceToDevice, stream);
  double rz = 0.0;
  if (!dot(r.get(), z.get(), &rz, error)) return false;
  for (;;) {
    apply(p.get(), q.get());
    filter.apply(q.get(), stream);
    double pq = 0.0;
    if (!dot(p.get(), q.get(), &pq, error)) return false;
    if (!(pq > 0.0)) return true;
    double rr = 0.0;
    if (!cgStep(rz / pq, &rr, error)) return false;
    ++result->iterations;
    result->relativeResidual = std::sqrt(rr) / bNorm;
    if (result->relativeResidual <= tolerance) {
      result->converged = true;
      return true;
    }
    if (result->iterations >= maxIterations) return true;
    precondition();
    double rzNext = 0.0;
    if (!dot(r.get(), z.get(), &rzNext, error)) return false;
    xpbyKernel<<<launch::blocks(cells()), launch::kThreads, 0, stream>>>(cells(), z.get(), rzNext / rz, p.get());
    rz = rzNext;
  }
}

DevicePressureSolver::DevicePressureSolver(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DevicePressureSolver::~DevicePressureSolver() = default;

std::unique_ptr<DevicePressureSolver> DevicePressureSolver::create(const PressureSolveView& view, std::string* error) {
  if (view.levels.empty()) {
    if (error) *error = "pressure solve view: no multigrid levels";
    return nullptr;
  }
  auto d = std::make_unique<Impl>();
  const kernels::PoissonStencil<double>& s = view.fine;
  const size_t nx = static_cast<size_t>(s.nx), ny = static_cast<size_t>(s.ny), nz = static_cast<size_t>(s.nz);
  const size_t cells = nx * ny * nz;
  if (failed(cudaStreamCreateWithFlags(&d->stream, cudaStreamNonBlocking), error) ||
      failed(d->cu.upload(s.cu, (nx + 1) * ny * nz), error) || failed(d->cv.upload(s.cv, nx * (ny + 1) * nz), error) ||
      failed(d->cw.upload(s.cw, nx * ny * (nz + 1)), error) || failed(d->diagonal.upload(s.diagonal, cells), error))
    return nullptr;
  for (DeviceArray<double>* v : {&d->b, &d->x, &d->r, &d->z, &d->p, &d->q})
    if (failed(v->allocate(cells), error)) return nullptr;
  if (failed(d->scalars.allocate(4), error) ||
      !d->filter.upload(view.fineRegions, static_cast<int64_t>(cells), error) || !d->multigrid.upload(view, error) ||
      !d->multigrid.record(d->r.get(), d->z.get(), d->stream, error))
    return nullptr;
  d->op = s;
  d->op.cu = d->cu.get();
  d->op.cv = d->cv.get();
  d->op.cw = d->cw.get();
  d->op.diagonal = d->diagonal.get();
  d->op.span = nullptr;
  // The uploads ran on the legacy stream, which a non-blocking stream does not wait for.
  if (failed(cudaDeviceSynchronize(), error)) return nullptr;
  return std::unique_ptr<DevicePressureSolver>(new DevicePressureSolver(std::move(d)));
}

bool DevicePressureSolver::vcycle(const double* r, double* z, std::string* error) {
  Impl& d = *impl_;
  if (failed(cudaMemcpyAsync(d.r.get(), r, d.bytes(), cudaMemcpyHostToDevice, d.stream), error)) return false;
  d.multigrid.launch(d.stream);
  return !failed(cudaMemcpyAsync(z, d.z.get(), d.bytes(), cudaMemcpyDeviceToHost, d.stream), error) &&
         !failed(cudaStreamSynchronize(d.stream), error);
}

bool DevicePressureSolver::solve(const double* b, double* x, double tolerance, int maxIterations,
                                 DevicePressureResult* result, std::string* error) {
  Impl& d = *impl_;
  if (failed(cudaMemcpyAsync(d.b.get(), b, d.bytes(), cudaMemcpyHostToDevice, d.stream), error) ||
      failed(cudaMemcpyAsync(d.x.get(), x, d.bytes(), cudaMemcpyHostToDevice, d.stream), error) ||
      failed(cudaStreamSynchronize(d.stream), error))
    return false;
  return solveResident(tolerance, maxIterations, result, error) &&
         !failed(cudaMemcpyAsync(x, d.x.get(), d.bytes(), cudaMemcpyDeviceToHost, d.stream), error) &&
         !failed(cudaStreamSynchronize(d.stream), error);
}

bool DevicePressureSolver::solveResident(double tolerance, int maxIterations, DevicePressureResult* result,
                                         std::string* error) {
  Impl& d = *impl_;
  if (failed(cudaDeviceSynchronize(), error)) return false;  // the caller's work on the legacy stream
  EventTimer timer(d.stream);
  timer.start();
  const bool solved = d.solve(tolerance, maxIterations, result, error);
  result->ms = timer.stopMs();
  return solved;
}

double* DevicePressureSolver::rhs() const { return impl_->b.get(); }
double* DevicePressureSolver::solution() const { return impl_->x.get(); }

bool DevicePressureSolver::timeVcycle(int repeats, double* msPerCycle, double* msPerApply, std::string* error) {
  Impl& d = *impl_;
  const int n = repeats > 0 ? repeats : 1;
  if (failed(cudaMemsetAsync(d.r.get(), 0, d.bytes(), d.stream), error)) return false;
  d.multigrid.launch(d.stream);  // warm-up
  EventTimer timer(d.stream);
  timer.start();
  for (int i = 0; i < n; ++i) d.multigrid.launch(d.stream);
  *msPerCycle = timer.stopMs() / n;
  d.apply(d.r.get(), d.q.get());
  timer.start();
  for (int i = 0; i < n; ++i) d.apply(d.r.get(), d.q.get());
  *msPerApply = timer.stopMs() / n;
  return !failed(cudaStreamSynchronize(d.stream), error);
}

}  // namespace vp::gpu
