#include <cuda_runtime.h>

#include <cmath>
#include <cub/block/block_reduce.cuh>
#include <utility>
#include <vector>

#include "device_support.cuh"
#include "gpu_kernels/constraint_kernels.h"
#include "gpu_kernels/device_block_system.h"
#include "gpu_kernels/vector_kernels.h"

namespace vp::gpu {
namespace {

using kernels::BinBcsrView;

// Three warps per bin (one per row of the 3x3 blocks), kBinsPerBlock bins per thread block,
// so the three components of a block row are always in one thread block.
constexpr int kBinsPerBlock = 2;
constexpr int kThreads = 3 * kernels::kBinRows * kBinsPerBlock;
using BlockReduce = cub::BlockReduce<double, kThreads>;

// The fused CG's scalars. Each lives in a ring indexed by the iteration, so that the kernel
// that clears a slot for a later iteration never races a reader of the current one.
struct CgScalars {
  double pq[2];  // p . A p of iteration it: pq[it % 2]
  double rz[3];  // r . z before iteration it: rz[it % 3]
  double rr[2];  // r . r after iteration it: rr[it % 2]
  double bb;     // |filtered b|^2
  double initialRR;
  double finalRR;
  int stoppedAt;  // iterations done when the solve stopped; -1 while running
};

// Thread 0 of the block adds the block's sum of `value` to *target.
__device__ void addBlockSum(double value, double* target) {
  __shared__ typename BlockReduce::TempStorage storage;
  const double sum = BlockReduce(storage).Sum(value);
  if (threadIdx.x == 0) atomicAdd(target, sum);
  __syncthreads();  // the storage is reused by the caller's next sum
}

// The scalar row a thread owns.
struct DofThread {
  int32_t row;
  int component;
  int64_t dof;
  bool valid;
};

__device__ DofThread dofThread(int32_t rows) {
  const int warp = threadIdx.x / kernels::kBinRows, lane = threadIdx.x % kernels::kBinRows;
  const int32_t bin = blockIdx.x * kBinsPerBlock + warp / 3;
  DofThread t;
  t.row = bin * kernels::kBinRows + lane;
  t.component = warp % 3;
  t.dof = 3 * static_cast<int64_t>(t.row) + t.component;
  t.valid = t.row < rows;
  return t;
}

__global__ void binMultiplyKernel(BinBcsrView<double> m, const double* x, double* y) {
  const DofThread t = dofThread(m.rows);
  if (t.valid) y[t.dof] = kernels::binBcsrComponentProduct(t.row, t.component, m, x);
}

__global__ void bcsrMultiplyKernel(int rows, const int32_t* rowStart, const int32_t* columns, const double* values,
                                   const double* x, double* y) {
  const int row = blockIdx.x * blockDim.x + threadIdx.x;
  if (row < rows) kernels::bcsrRowProduct(row, rowStart, columns, values, x, y);
}

// The node constraints, for threads that own one component each.
struct Constraints {
  const uint8_t* kind;
  const double* normal;

  // Writes `value` to v at t's component and returns it filtered (also written to v). Every
  // thread of the block must call it: the row's other components come from other warps.
  __device__ double filterInBlock(const DofThread& t, double value, double* v) const {
    if (t.valid) v[t.dof] = value;
    __syncthreads();
    double filtered = 0;
    if (t.valid) {
      const double* row = v + 3 * static_cast<int64_t>(t.row);
      filtered = kernels::filteredComponent(kind[t.row], normal + 3 * static_cast<int64_t>(t.row), row[0], row[1],
                                            row[2], t.component);
    }
    __syncthreads();
    if (t.valid) v[t.dof] = filtered;
    return filtered;
  }
};

// z = F D^-1 r at t's component, once r is complete for t's block row.
__device__ double preconditionInBlock(const DofThread& t, const double* inverseDiagonal, const Constraints& c,
                                      const double* r, double* z) {
  __syncthreads();  // the block row's r
  const double value = t.valid ? kernels::blockJacobiComponent(t.row, t.component, inverseDiagonal, r) : 0.0;
  return c.filterInBlock(t, value, z);
}

// r = F (b - A x), z = F D^-1 r, p = z; sums r.z, r.r and |F b|^2 (F b is left in p until
// p is written).
__global__ void cgStartKernel(BinBcsrView<double> m, const double* inverseDiagonal, Constraints c, const double* b,
                              const double* x, double* r, double* z, double* p, CgScalars* s) {
  const DofThread t = dofThread(m.rows);
  const double fb = c.filterInBlock(t, t.valid ? b[t.dof] : 0.0, p);
  const double ax = t.valid ? kernels::binBcsrComponentProduct(t.row, t.component, m, x) : 0.0;
  const double rc = c.filterInBlock(t, t.valid ? b[t.dof] - ax : 0.0, r);
  const double zc = preconditionInBlock(t, inverseDiagonal, c, r, z);
  if (t.valid) p[t.dof] = zc;
  addBlockSum(rc * zc, &s->rz[0]);
  addBlockSum(rc * rc, &s->initialRR);
  addBlockSum(fb * fb, &s->bb);
}

// x -= F x: what the CPU's CG returns when nothing drives the system.
__global__ void removeFreePartKernel(int rows, Constraints c, double* x, double* scratch) {
  const DofThread t = dofThread(rows);
  const double fx = c.filterInBlock(t, t.valid ? x[t.dof] : 0.0, scratch);
  if (t.valid) x[t.dof] -= fx;
}

// Fused launch 1: q = F A p, with p . q.
__global__ void cgApplyKernel(int it, BinBcsrView<double> m, Constraints c, const double* p, double* q, CgScalars* s) {
  if (s->stoppedAt >= 0) return;
  const DofThread t = dofThread(m.rows);
  const double ap = t.valid ? kernels::binBcsrComponentProduct(t.row, t.component, m, p) : 0.0;
  const double qc = c.filterInBlock(t, ap, q);
  addBlockSum(t.valid ? p[t.dof] * qc : 0.0, &s->pq[it % 2]);
}

// Fused launch 2: x += a p, r -= a q, z = F D^-1 r, with r.z and r.r.
__global__ void cgUpdateKernel(int it, int rows, const double* inverseDiagonal, Constraints c, const double* p,
                               const double* q, double* x, double* r, double* z, CgScalars* s) {
  if (s->stoppedAt >= 0) return;
  const double pq = s->pq[it % 2];
  const double alpha = pq > 0 ? s->rz[it % 3] / pq : 0.0;
  const DofThread t = dofThread(rows);
  if (t.valid) {
    kernels::axpyItem<double>(t.dof, alpha, p, x);
    kernels::axpyItem<double>(t.dof, -alpha, q, r);
  }
  const double zc = preconditionInBlock(t, inverseDiagonal, c, r, z);
  const double rc = t.valid ? r[t.dof] : 0.0;
  addBlockSum(rc * zc, &s->rz[(it + 1) % 3]);
  addBlockSum(rc * rc, &s->rr[it % 2]);
}

// Fused launch 3: stop, or p = z + beta p; clears the slots the next iteration sums into.
__global__ void cgDirectionKernel(int it, int rows, double toleranceSquared, int maxIterations, const double* z,
                                  double* p, CgScalars* s) {
  if (s->stoppedAt >= 0) return;
  const double rr = s->rr[it % 2];
  const bool breakdown = !(s->pq[it % 2] > 0);
  const bool done = breakdown || rr <= toleranceSquared * s->bb || it + 1 >= maxIterations;
  const bool first = blockIdx.x == 0 && threadIdx.x == 0;
  if (done) {
    if (first) {
      s->finalRR = rr;  // after a breakdown alpha was 0: the residual of the iteration before
      s->stoppedAt = breakdown ? it : it + 1;
    }
    return;
  }
  const double beta = s->rz[(it + 1) % 3] / s->rz[it % 3];
  const DofThread t = dofThread(rows);
  if (t.valid) kernels::xpbyItem<double>(t.dof, z, beta, p);
  if (first) {
    s->rz[(it + 2) % 3] = 0;
    s->pq[(it + 1) % 2] = 0;
    s->rr[(it + 1) % 2] = 0;
  }
}

// The unfused form's pieces.
__global__ void filteredMultiplyKernel(BinBcsrView<double> m, Constraints c, const double* x, double* y) {
  const DofThread t = dofThread(m.rows);
  c.filterInBlock(t, t.valid ? kernels::binBcsrComponentProduct(t.row, t.component, m, x) : 0.0, y);
}

__global__ void dotKernel(int64_t n, const double* a, const double* b, double* target) {
  const int64_t i = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  addBlockSum(i < n ? a[i] * b[i] : 0.0, target);
}

__global__ void axpyKernel(int64_t n, double a, const double* x, double* y) {
  const int64_t i = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  if (i < n) kernels::axpyItem(i, a, x, y);
}

__global__ void xpbyKernel(int64_t n, const double* x, double b, double* y) {
  const int64_t i = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  if (i < n) kernels::xpbyItem(i, x, b, y);
}

__global__ void preconditionKernel(int rows, const double* inverseDiagonal, Constraints c, const double* r, double* z) {
  preconditionInBlock(dofThread(rows), inverseDiagonal, c, r, z);
}

unsigned blocksFor(int64_t n) { return static_cast<unsigned>((n + kThreads - 1) / kThreads); }

// Thread blocks for the scalar rows of `rows` block rows (whole bins, kBinsPerBlock a block).
unsigned blocksForRows(int32_t rows) {
  const int32_t bins = (rows + kernels::kBinRows - 1) / kernels::kBinRows;
  return static_cast<unsigned>((bins + kBinsPerBlock - 1) / kBinsPerBlock);
}

}  // namespace

struct DeviceBlockSystem::Impl {
  BinBcsrView<double> matrix;  // device pointers
  int32_t rows = 0;
  int64_t bcsrBlocks = 0;
  DeviceArray<int32_t> binSlotStart, columns, diagonalPosition, bcsrRowStart, bcsrColumns;
  DeviceArray<double> values, diagonal, inverseDiagonal, nodeNormal, bcsrValues;
  DeviceArray<uint8_t> nodeKind;
  DeviceArray<double> b, x, r, z, p, q;
  DeviceArray<CgScalars> scalars;

  int64_t dofs() const { return 3 * static_cast<int64_t>(rows); }
  size_t laneEntries() const { return values.size(); }
  Constraints constraints() const { return Constraints{nodeKind.get(), nodeNormal.get()}; }

  bool upload(const HostBlockSystem& host, std::string* error) {
    const kernels::BinBcsrView<double>& m = host.matrix;
    rows = m.rows;
    const size_t lanes = static_cast<size_t>(host.slots) * kernels::kBinRows;
    const size_t diagonalEntries = static_cast<size_t>(m.bins) * 9 * kernels::kBinRows;
    if (failed(binSlotStart.upload(m.binSlotStart, static_cast<size_t>(m.bins) + 1), error) ||
        failed(columns.upload(m.columns, lanes), error) || failed(values.upload(m.values, 9 * lanes), error) ||
        failed(diagonal.upload(m.diagonal, diagonalEntries), error) ||
        failed(diagonalPosition.upload(m.diagonalPosition, static_cast<size_t>(rows)), error) ||
        failed(inverseDiagonal.upload(host.inverseDiagonal, diagonalEntries), error) ||
        failed(nodeKind.allocate(static_cast<size_t>(rows)), error) ||
        failed(nodeNormal.allocate(static_cast<size_t>(dofs())), error) ||
        !uploadConstraints(host.nodeKind, host.nodeNormal, error))
      return false;
    for (DeviceArray<double>* v : {&b, &x, &r, &z, &p, &q})
      if (failed(v->allocate(static_cast<size_t>(dofs())), error)) return false;
    if (failed(scalars.allocate(1), error)) return false;
    if (host.bcsrRowStart) {
      bcsrBlocks = host.bcsrRowStart[rows];
      if (failed(bcsrRowStart.upload(host.bcsrRowStart, static_cast<size_t>(rows) + 1), error) ||
          failed(bcsrColumns.upload(host.bcsrColumns, static_cast<size_t>(bcsrBlocks)), error) ||
          failed(bcsrValues.upload(host.bcsrValues, 9 * static_cast<size_t>(bcsrBlocks)), error))
        return false;
    }
    matrix = m;
    matrix.binSlotStart = binSlotStart.get();
    matrix.columns = columns.get();
    matrix.values = values.get();
    matrix.diagonal = diagonal.get();
    matrix.diagonalPosition = diagonalPosition.get();
    return true;
  }

  bool uploadConstraints(const uint8_t* kind, const double* normal, std::string* error) {
    if (!kind) return !failed(cudaMemset(nodeKind.get(), kernels::kNodeFree, static_cast<size_t>(rows)), error);
    return !failed(cudaMemcpy(nodeKind.get(), kind, static_cast<size_t>(rows), cudaMemcpyHostToDevice), error) &&
           !failed(cudaMemcpy(nodeNormal.get(), normal, static_cast<size_t>(dofs()) * sizeof(double),
                              cudaMemcpyHostToDevice),
                   error);
  }

  void launchMultiply(bool bcsr, const double* in, double* out) {
    if (bcsr)
      bcsrMultiplyKernel<<<blocksFor(rows), kThreads>>>(rows, bcsrRowStart.get(), bcsrColumns.get(), bcsrValues.get(),
                                                        in, out);
    else
      binMultiplyKernel<<<blocksForRows(rows), kThreads>>>(matrix, in, out);
  }

  CgScalars readScalars() {
    CgScalars s{};
    cudaMemcpy(&s, scalars.get(), sizeof s, cudaMemcpyDeviceToHost);
    return s;
  }

  // r, z, p and the scalars for a solve from the current x; the initial |r|^2 and |F b|^2.
  void start() {
    CgScalars zero{};
    zero.stoppedAt = -1;
    cudaMemcpy(scalars.get(), &zero, sizeof zero, cudaMemcpyHostToDevice);
    cgStartKernel<<<blocksForRows(rows), kThreads>>>(matrix, inverseDiagonal.get(), constraints(), b.get(), x.get(),
                                                     r.get(), z.get(), p.get(), scalars.get());
  }

  // The host's look every kStopCheckInterval iterations: the device's stop, or the caller's.
  bool stopChecked(int iterations, double bb, const DeviceCgControl& control, DeviceCgResult* result) {
    const CgScalars s = readScalars();
    if (s.stoppedAt >= 0) return true;
    const double relative = bb > 0 ? std::sqrt(s.rr[(iterations - 1) % 2] / bb) : 0.0;
    if (!control.stop || !control.stop(control.context, iterations, relative)) return false;
    result->stoppedByCaller = true;
    CgScalars stopped = s;
    stopped.stoppedAt = iterations;
    stopped.finalRR = s.rr[(iterations - 1) % 2];
    cudaMemcpy(scalars.get(), &stopped, sizeof stopped, cudaMemcpyHostToDevice);
    return true;
  }

  void iterateFused(double toleranceSquared, int maxIterations, double bb, const DeviceCgControl& control,
                    DeviceCgResult* result) {
    const unsigned blocks = blocksForRows(rows);
    for (int it = 0; it < maxIterations; ++it) {
      cgApplyKernel<<<blocks, kThreads>>>(it, matrix, constraints(), p.get(), q.get(), scalars.get());
      cgUpdateKernel<<<blocks, kThreads>>>(it, rows, inverseDiagonal.get(), constraints(), p.get(), q.get(), x.get(),
                                           r.get(), z.get(), scalars.get());
      cgDirectionKernel<<<blocks, kThreads>>>(it, rows, toleranceSquared, maxIterations, z.get(), p.get(),
                                              scalars.get());
      result->launches += 3;
      if (((it + 1) % kStopCheckInterval == 0 || it + 1 == maxIterations) &&
          stopChecked(it + 1, bb, control, result))
        return;
    }
  }

  void iterateUnfused(double toleranceSquared, int maxIterations, double bb, double rz,
                      const DeviceCgControl& control, DeviceCgResult* result) {
    const unsigned blocks = blocksForRows(rows), dofBlocks = blocksFor(dofs());
    double* sums = &scalars.get()->pq[0];  // two scratch sums on the device
    for (int it = 0; it < maxIterations; ++it) {
      filteredMultiplyKernel<<<blocks, kThreads>>>(matrix, constraints(), p.get(), q.get());
      cudaMemset(sums, 0, 2 * sizeof(double));
      dotKernel<<<dofBlocks, kThreads>>>(dofs(), p.get(), q.get(), sums);
      double pq = 0;
      cudaMemcpy(&pq, sums, sizeof pq, cudaMemcpyDeviceToHost);
      if (!(pq > 0)) break;
      const double alpha = rz / pq;
      axpyKernel<<<dofBlocks, kThreads>>>(dofs(), alpha, p.get(), x.get());
      axpyKernel<<<dofBlocks, kThreads>>>(dofs(), -alpha, q.get(), r.get());
      preconditionKernel<<<blocks, kThreads>>>(rows, inverseDiagonal.get(), constraints(), r.get(), z.get());
      cudaMemset(sums, 0, 2 * sizeof(double));
      dotKernel<<<dofBlocks, kThreads>>>(dofs(), r.get(), z.get(), sums);
      dotKernel<<<dofBlocks, kThreads>>>(dofs(), r.get(), r.get(), sums + 1);
      double next[2];
      cudaMemcpy(next, sums, sizeof next, cudaMemcpyDeviceToHost);
      result->launches += 7;
      result->iterations = it + 1;
      result->relativeResidual = bb > 0 ? std::sqrt(next[1] / bb) : 0.0;
      if (next[1] <= toleranceSquared * bb) break;
      if ((it + 1) % kStopCheckInterval == 0 && control.stop &&
          control.stop(control.context, it + 1, result->relativeResidual)) {
        result->stoppedByCaller = true;
        break;
      }
      xpbyKernel<<<dofBlocks, kThreads>>>(dofs(), z.get(), next[0] / rz, p.get());
      result->launches += 1;
      rz = next[0];
    }
  }
};

DeviceBlockSystem::DeviceBlockSystem(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceBlockSystem::~DeviceBlockSystem() = default;

std::unique_ptr<DeviceBlockSystem> DeviceBlockSystem::create(const HostBlockSystem& host, std::string* error) {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess || count == 0) {
    cudaGetLastError();
    if (error) *error = "no CUDA device";
    return nullptr;
  }
  auto impl = std::make_unique<Impl>();
  if (!impl->upload(host, error)) return nullptr;
  return std::unique_ptr<DeviceBlockSystem>(new DeviceBlockSystem(std::move(impl)));
}

int32_t DeviceBlockSystem::rows() const { return impl_->rows; }

bool DeviceBlockSystem::multiply(const double* x, double* y, bool bcsr, std::string* error) {
  Impl& d = *impl_;
  if (bcsr && !d.bcsrRowStart.get()) {
    if (error) *error = "created without its BCSR copy";
    return false;
  }
  const size_t bytes = static_cast<size_t>(d.dofs()) * sizeof(double);
  if (failed(cudaMemcpy(d.x.get(), x, bytes, cudaMemcpyHostToDevice), error)) return false;
  d.launchMultiply(bcsr, d.x.get(), d.q.get());
  return !failed(cudaMemcpy(y, d.q.get(), bytes, cudaMemcpyDeviceToHost), error);
}

bool DeviceBlockSystem::timeMultiply(int repeats, bool bcsr, double* msPerProduct, std::string* error) {
  Impl& d = *impl_;
  if (bcsr && !d.bcsrRowStart.get()) {
    if (error) *error = "created without its BCSR copy";
    return false;
  }
  if (failed(cudaMemset(d.x.get(), 0, static_cast<size_t>(d.dofs()) * sizeof(double)), error)) return false;
  d.launchMultiply(bcsr, d.x.get(), d.q.get());  // warm-up
  EventTimer timer;
  timer.start();
  for (int i = 0; i < repeats; ++i) d.launchMultiply(bcsr, d.x.get(), d.q.get());
  const double ms = timer.stopMs();
  if (failed(cudaSuccess, error)) return false;
  *msPerProduct = ms / (repeats > 0 ? repeats : 1);
  return true;
}

bool DeviceBlockSystem::setValues(const double* values, const double* diagonal, const double* inverseDiagonal,
                                  std::string* error) {
  Impl& d = *impl_;
  return !failed(cudaMemcpy(d.values.get(), values, d.values.size() * sizeof(double), cudaMemcpyHostToDevice), error) &&
         !failed(cudaMemcpy(d.diagonal.get(), diagonal, d.diagonal.size() * sizeof(double), cudaMemcpyHostToDevice),
                 error) &&
         !failed(cudaMemcpy(d.inverseDiagonal.get(), inverseDiagonal, d.inverseDiagonal.size() * sizeof(double),
                            cudaMemcpyHostToDevice),
                 error);
}

bool DeviceBlockSystem::setConstraints(const uint8_t* nodeKind, const double* nodeNormal, std::string* error) {
  return impl_->uploadConstraints(nodeKind, nodeNormal, error);
}

bool DeviceBlockSystem::solve(const double* b, double* x, double relativeTolerance, int maxIterations,
                              DeviceCgForm form, DeviceCgResult* result, std::string* error,
                              const DeviceCgControl& control) {
  Impl& d = *impl_;
  *result = DeviceCgResult{};
  const size_t bytes = static_cast<size_t>(d.dofs()) * sizeof(double);
  if (failed(cudaMemcpy(d.b.get(), b, bytes, cudaMemcpyHostToDevice), error) ||
      failed(cudaMemcpy(d.x.get(), x, bytes, cudaMemcpyHostToDevice), error))
    return false;
  d.start();
  const CgScalars initial = d.readScalars();
  if (failed(cudaSuccess, error)) return false;
  const double toleranceSquared = relativeTolerance * relativeTolerance;
  if (initial.bb == 0) {
    removeFreePartKernel<<<blocksForRows(d.rows), kThreads>>>(d.rows, d.constraints(), d.x.get(), d.z.get());
    result->converged = true;
  } else if (initial.initialRR <= toleranceSquared * initial.bb || maxIterations <= 0) {
    result->relativeResidual = std::sqrt(initial.initialRR / initial.bb);
    result->converged = initial.initialRR <= toleranceSquared * initial.bb;
  } else {
    EventTimer timer;
    timer.start();
    if (form == DeviceCgForm::Fused) {
      d.iterateFused(toleranceSquared, maxIterations, initial.bb, control, result);
      const CgScalars s = d.readScalars();
      result->iterations = s.stoppedAt;
      result->relativeResidual = std::sqrt(s.finalRR / initial.bb);
    } else {
      d.iterateUnfused(toleranceSquared, maxIterations, initial.bb, initial.rz[0], control, result);
    }
    result->deviceMs = timer.stopMs();
    result->converged = result->relativeResidual <= relativeTolerance;
  }
  if (failed(cudaSuccess, error)) return false;
  return !failed(cudaMemcpy(x, d.x.get(), bytes, cudaMemcpyDeviceToHost), error);
}

DeviceBcsr DeviceBlockSystem::bcsr() const {
  DeviceBcsr out;
  out.rows = impl_->rows;
  if (!impl_->bcsrRowStart.get()) return out;
  out.blocks = impl_->bcsrBlocks;
  out.rowStart = impl_->bcsrRowStart.get();
  out.columns = impl_->bcsrColumns.get();
  out.values = impl_->bcsrValues.get();
  out.x = impl_->x.get();
  out.y = impl_->q.get();
  return out;
}

}  // namespace vp::gpu
