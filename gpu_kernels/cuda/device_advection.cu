// Built with --fmad=false (gpu_kernels/CMakeLists.txt): the advection's bits are the CPU's.
#include <cuda_runtime.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "device_support.cuh"
#include "gpu_kernels/device_advection.h"
#include "gpu_kernels/scalar_advection_kernels.h"

namespace vp::gpu {
namespace {

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
  const int64_t f = launch::index();
  int at[3];
  if (!faceOf(v, a, f, at)) return;
  out[f] = lo != nullptr ? kernels::advectFace(v, a, at, dt, v.u[a], lo + f, hi + f)
                         : kernels::advectFace(v, a, at, dt, v.u[a]);
}

__global__ void correctionKernel(kernels::MacVelocityView v, int a, double dt, const double* forward, const double* lo,
                                 const double* hi, double* out) {
  const int64_t f = launch::index();
  int at[3];
  if (faceOf(v, a, f, at)) out[f] = kernels::maccormackFace(v, a, at, f, dt, v.u[a], forward, lo[f], hi[f]);
}

// Cell c of the cell lattice as (i, j, k).
__device__ bool cellOf(const kernels::MacLayout& g, int64_t c, int at[3]) {
  if (c >= g.nx * g.ny * g.nz) return false;
  at[0] = static_cast<int>(c % g.nx);
  at[1] = static_cast<int>((c / g.nx) % g.ny);
  at[2] = static_cast<int>(c / (g.nx * g.ny));
  return true;
}

// Every cell's trace back over dt.
__global__ void traceCellsKernel(kernels::MacVelocityView v, kernels::MacLayout g, double dt, double* back) {
  const int64_t c = launch::index();
  int at[3];
  if (cellOf(g, c, at)) kernels::traceCell(v, at, dt, back + 3 * c);
}

__global__ void scalarForwardKernel(kernels::ScalarCellRules rules, int64_t cells, const double* old,
                                    const double* back, double* forward, double* lo, double* hi) {
  const int64_t c = launch::index();
  if (c < cells) kernels::scalarForwardCell(rules, old, c, back + 3 * c, forward, lo, hi);
}

// MacCormack's correction, sampling the forward field at each cell's back-trace reflected
// through the cell.
__global__ void scalarCorrectionKernel(kernels::ScalarCellRules rules, kernels::MacLayout g, const double* old,
                                       const double* forward, const double* back, const double* lo, const double* hi,
                                       double* out) {
  const int64_t c = launch::index();
  int at[3];
  if (!cellOf(g, c, at)) return;
  double ahead[3];
  kernels::reflectThrough(at, back + 3 * c, ahead);
  out[c] = kernels::scalarCorrectionCell(rules, old, forward, c, ahead, lo[c], hi[c]);
}

__global__ void rowSumKernel(const double* values, int64_t nx, int64_t rows, double* rowSums) {
  const int64_t row = launch::index();
  if (row < rows) rowSums[row] = kernels::cellRowSum(values, nx, row);
}

// One thread: the rows' sums added in row order, as the CPU adds them; minus the Open sides'
// outflow when `velocity` is given (the target before advection).
__global__ void totalKernel(const double* rowSums, int64_t rows, kernels::MacLayout g,
                            kernels::MacVelocityView velocity, bool outflow, const double* values, double dt,
                            double* total) {
  double sum = 0.0;
  for (int64_t row = 0; row < rows; ++row) sum += rowSums[row];
  *total = outflow ? sum - kernels::openSideOutflow(g, velocity.u, values, dt, velocity.h) : sum;
}

__global__ void rescaleKernel(int64_t cells, const double* target, const double* total, double* values) {
  const int64_t c = launch::index();
  if (c < cells) values[c] *= kernels::conservationScale(*target, *total);
}

}  // namespace

struct DeviceAdvection::Impl {
  kernels::MacVelocityView view{};  // device pointers: the current velocity
  kernels::MacLayout layout{};
  DeviceArray<double> u[3], advected[3], forward, lo, hi;

  size_t faces(int a) const {
    return static_cast<size_t>(view.faceDims[a][0]) * view.faceDims[a][1] * view.faceDims[a][2];
  }
  // As advectVelocity: every axis reads the old velocity; the new one is swapped in at the end.
  void advect(double dt, bool maccormack) {
    for (int a = 0; a < 3; ++a) {
      const unsigned blocks = launch::blocks(static_cast<int64_t>(faces(a)));
      if (!maccormack) {
        forwardKernel<<<blocks, launch::kThreads>>>(view, a, dt, advected[a].get(), nullptr, nullptr);
        continue;
      }
      forwardKernel<<<blocks, launch::kThreads>>>(view, a, dt, forward.get(), lo.get(), hi.get());
      correctionKernel<<<blocks, launch::kThreads>>>(view, a, dt, forward.get(), lo.get(), hi.get(), advected[a].get());
    }
    for (int a = 0; a < 3; ++a) {
      u[a].swap(advected[a]);
      view.u[a] = u[a].get();
    }
  }
};

DeviceAdvection::DeviceAdvection(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceAdvection::~DeviceAdvection() = default;

std::unique_ptr<DeviceAdvection> DeviceAdvection::create(const kernels::MacVelocityView& host,
                                                         const kernels::MacLayout& layout, std::string* error) {
  auto d = std::make_unique<Impl>();
  d->view = host;
  d->layout = layout;
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
  return std::unique_ptr<DeviceAdvection>(new DeviceAdvection(std::move(d)));
}

bool DeviceAdvection::advect(double dt, bool maccormack, std::string* error) {
  impl_->advect(dt, maccormack);
  return !failed(cudaDeviceSynchronize(), error);
}

// ScalarAdvectionSlices' passes: the conserved field's target, the traces shared by all fields,
// then per field its forward pass, its correction, and the conserved field's rescale.
bool DeviceAdvection::advectScalars(double* const* fields, int count, double dt, bool maccormack,
                                    const ScalarAdvectionOptions& options, std::string* error) {
  if (count <= 0) return true;
  const kernels::MacLayout& g = impl_->layout;
  const int64_t cells = g.nx * g.ny * g.nz, rows = g.ny * g.nz;
  const size_t n = static_cast<size_t>(cells), bytes = n * sizeof(double);
  std::vector<DeviceArray<double>> values(static_cast<size_t>(count));
  // The velocity's MacCormack scratch (sized for the largest face lattice, more than the cells)
  // serves the scalars too.
  DeviceArray<double>& forward = impl_->forward;
  DeviceArray<double>& lo = impl_->lo;
  DeviceArray<double>& hi = impl_->hi;
  DeviceArray<double> out, back, rowSums, sums, solid;
  DeviceArray<uint8_t> faces, blockOpen;
  for (int f = 0; f < count; ++f)
    if (failed(values[static_cast<size_t>(f)].upload(fields[f], n), error)) return false;
  if (failed(out.allocate(n), error) || failed(back.allocate(3 * n), error) ||
      failed(rowSums.allocate(static_cast<size_t>(rows)), error) || failed(sums.allocate(2), error))
    return false;
  if (options.faces != nullptr &&
      (failed(faces.upload(options.faces, n), error) || failed(blockOpen.upload(options.blockOpen, n), error)))
    return false;
  if (options.solidValues != nullptr && failed(solid.upload(options.solidValues, static_cast<size_t>(count)), error))
    return false;
  const bool conserve = options.conservedField >= 0 && options.conservedField < count;
  auto total = [&](const double* field, bool outflow, double* into) {
    rowSumKernel<<<launch::blocks(rows), launch::kThreads>>>(field, g.nx, rows, rowSums.get());
    totalKernel<<<1, 1>>>(rowSums.get(), rows, g, impl_->view, outflow, field, dt, into);
  };
  if (conserve) total(values[static_cast<size_t>(options.conservedField)].get(), true, sums.get());
  traceCellsKernel<<<launch::blocks(cells), launch::kThreads>>>(impl_->view, g, dt, back.get());
  for (int f = 0; f < count; ++f) {
    double* field = values[static_cast<size_t>(f)].get();
    const kernels::ScalarCellRules rules{faces.get(),
                                         options.faces ? blockOpen.get() : nullptr,
                                         nullptr,
                                         options.solidValues ? solid.get() + f : nullptr,
                                         {static_cast<int>(g.nx), static_cast<int>(g.ny), static_cast<int>(g.nz)}};
    double* fwd = maccormack ? forward.get() : out.get();
    double* low = maccormack ? lo.get() : nullptr;
    double* high = maccormack ? hi.get() : nullptr;
    scalarForwardKernel<<<launch::blocks(cells), launch::kThreads>>>(rules, cells, field, back.get(), fwd, low, high);
    if (maccormack)
      scalarCorrectionKernel<<<launch::blocks(cells), launch::kThreads>>>(rules, g, field, forward.get(), back.get(),
                                                                          lo.get(), hi.get(), out.get());
    if (failed(cudaMemcpy(field, out.get(), bytes, cudaMemcpyDeviceToDevice), error)) return false;
    if (conserve && f == options.conservedField) {
      total(field, false, sums.get() + 1);
      rescaleKernel<<<launch::blocks(cells), launch::kThreads>>>(cells, sums.get(), sums.get() + 1, field);
    }
  }
  for (int f = 0; f < count; ++f)
    if (failed(cudaMemcpy(fields[f], values[static_cast<size_t>(f)].get(), bytes, cudaMemcpyDeviceToHost), error))
      return false;
  return true;
}

bool DeviceAdvection::download(double* const u[3], std::string* error) {
  for (int a = 0; a < 3; ++a)
    if (failed(cudaMemcpy(u[a], impl_->u[a].get(), impl_->faces(a) * sizeof(double), cudaMemcpyDeviceToHost), error))
      return false;
  return true;
}

bool DeviceAdvection::timeAdvect(int repeats, double dt, bool maccormack, double* msPerAdvect, std::string* error) {
  const int n = repeats > 0 ? repeats : 1;
  impl_->advect(dt, maccormack);  // warm-up
  EventTimer timer;
  timer.start();
  for (int i = 0; i < n; ++i) impl_->advect(dt, maccormack);
  *msPerAdvect = timer.stopMs() / n;
  return !failed(cudaDeviceSynchronize(), error);
}

}  // namespace vp::gpu
