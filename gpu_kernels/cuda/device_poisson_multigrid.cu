#include "device_poisson_multigrid.cuh"

#include <algorithm>

namespace vp::gpu {
namespace {

// Levels (and boundary lists) this small are swept by one thread block that runs all of a
// smoothing's sweeps, synchronizing between half-sweeps, instead of two launches per sweep:
// there a launch costs more than the sweep.
constexpr int64_t kOneBlockCells = 4096;
constexpr int kOneBlockThreads = 1024;

__global__ void halfSweepKernel(kernels::PoissonStencil<float> s, const float* b, float* x, int colour) {
  int64_t cell;
  const int64_t t = launch::index();
  if (t < kernels::colourThreads(s) && kernels::colourCell(s, t, colour, &cell))
    kernels::gaussSeidelCell(s, cell, b, x);
}

// Launch bounds: a block of kOneBlockThreads must fit the registers of one multiprocessor.
__global__ void __launch_bounds__(kOneBlockThreads)
    oneBlockSweepsKernel(kernels::PoissonStencil<float> s, const float* b, float* x, int sweeps, bool reverse) {
  const int64_t threads = kernels::colourThreads(s);
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (int half = 0; half < 2; ++half) {
      const int colour = reverse ? 1 - half : half;
      for (int64_t t = threadIdx.x; t < threads; t += blockDim.x) {
        int64_t cell;
        if (kernels::colourCell(s, t, colour, &cell)) kernels::gaussSeidelCell(s, cell, b, x);
      }
      __syncthreads();
    }
}

// Boundary sweeps on compact values (multigrid_smoother.h, BoundaryCellLists): entries are
// the red list's cells, then the black's; values holds their x, then the constants they read.
struct BoundaryLists {
  const kernels::BoundaryCell* cells;
  const int32_t* reads;
  int64_t reds, count;
  int64_t nx, sz;
};

__global__ void boundaryGatherKernel(BoundaryLists l, const float* b, const float* x, float* values, float* rhs) {
  const int64_t e = launch::index();
  if (e >= l.count) return;
  const int64_t step[6] = {-1, 1, -l.nx, l.nx, -l.sz, l.sz};
  const int32_t cell = l.cells[e].cell;
  values[e] = x[cell];
  rhs[e] = b[cell];
  for (int f = 0; f < 6; ++f) {
    const int32_t at = l.reads[6 * e + f];
    if (at >= l.count) values[at] = x[cell + step[f]];
  }
}

__global__ void boundaryHalfKernel(BoundaryLists l, int colour, float* values, const float* rhs) {
  const int64_t begin = colour == 0 ? 0 : l.reds, end = colour == 0 ? l.reds : l.count;
  const int64_t e = begin + launch::index();
  if (e < end) values[e] = kernels::boundaryCellUpdate(l.cells[e], l.reads + 6 * e, values, rhs[e]);
}

__global__ void __launch_bounds__(kOneBlockThreads)
    oneBlockBoundarySweepsKernel(BoundaryLists l, int sweeps, bool reverse, float* values, const float* rhs) {
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (int half = 0; half < 2; ++half) {
      const int colour = reverse ? 1 - half : half;
      const int64_t begin = colour == 0 ? 0 : l.reds, end = colour == 0 ? l.reds : l.count;
      for (int64_t e = begin + threadIdx.x; e < end; e += blockDim.x)
        values[e] = kernels::boundaryCellUpdate(l.cells[e], l.reads + 6 * e, values, rhs[e]);
      __syncthreads();
    }
}

__global__ void boundaryScatterKernel(BoundaryLists l, const float* values, float* x) {
  const int64_t e = launch::index();
  if (e < l.count) x[l.cells[e].cell] = values[e];
}

__global__ void residualKernel(kernels::PoissonStencil<float> s, const float* b, const float* x, float* r) {
  const int64_t c = launch::index();
  if (c < s.nx * s.ny * s.nz) r[c] = kernels::residualCell(s, c, b, x);
}

// The restriction's three one-dimensional gathers (multigrid_transfer.h).
__global__ void restrictXKernel(kernels::TransferDims d, kernels::TransferSides sides, const float* scale,
                                const float* r, float* alongX) {
  const int64_t t = launch::index();
  if (t >= d.cx * d.ny * d.nz) return;
  const int64_t I = t % d.cx, row = t / d.cx;
  const kernels::AxisWeights w(I, d.nx, d.cx, sides, 0);
  alongX[t] = kernels::restrictAlongX(w, scale + d.nx * row, r + d.nx * row);
}

__global__ void restrictYKernel(kernels::TransferDims d, kernels::TransferSides sides, const float* alongX,
                                float* alongY) {
  const int64_t t = launch::index();
  if (t >= d.cx * d.cy * d.nz) return;
  const int64_t I = t % d.cx, J = (t / d.cx) % d.cy, k = t / (d.cx * d.cy);
  const kernels::AxisWeights w(J, d.ny, d.cy, sides, 1);
  alongY[t] = kernels::restrictAlong(w, alongX + I + d.cx * d.ny * k, d.cx);
}

__global__ void restrictZKernel(kernels::TransferDims d, kernels::TransferSides sides, const float* alongY,
                                const float* coarseDiagonal, float* coarseB) {
  const int64_t t = launch::index();
  if (t >= d.cx * d.cy * d.cz) return;
  const int64_t I = t % d.cx, J = (t / d.cx) % d.cy, K = t / (d.cx * d.cy);
  const kernels::AxisWeights w(K, d.nz, d.cz, sides, 2);
  const float v = kernels::restrictAlong(w, alongY + I + d.cx * J, d.cx * d.cy);
  coarseB[t] = coarseDiagonal[t] > 0.0f ? v : 0.0f;
}

__global__ void prolongateKernel(kernels::TransferDims d, kernels::TransferSides sides, const float* scale,
                                 const float* coarseX, float* fineX) {
  const int64_t c = launch::index();
  if (c >= d.nx * d.ny * d.nz) return;
  kernels::prolongateCell(d, sides, c % d.nx, (c / d.nx) % d.ny, c / (d.nx * d.ny), scale, coarseX, fineX);
}

template <class From, class To>
__global__ void convertKernel(int64_t n, const From* from, To* to) {
  const int64_t i = launch::index();
  if (i < n) to[i] = static_cast<To>(from[i]);
}

template <class T>
__global__ void regionSumKernel(int64_t cells, const int32_t* region, const uint8_t* floating, const T* v,
                                double* sum) {
  const int64_t c = launch::index();
  if (c >= cells) return;
  const int32_t r = region[c];
  if (r >= 0 && floating[r]) atomicAdd(sum + r, static_cast<double>(v[c]));
}

template <class T>
__global__ void regionFilterKernel(int64_t cells, const int32_t* region, const uint8_t* floating,
                                   const double* inverseCount, const double* sum, T* v) {
  const int64_t c = launch::index();
  if (c >= cells) return;
  const int32_t r = region[c];
  if (r < 0)
    v[c] = T(0);
  else if (floating != nullptr && floating[r])
    v[c] = static_cast<T>(v[c] - sum[r] * inverseCount[r]);
}

}  // namespace

bool DeviceRegionFilter::upload(const RegionView& view, int64_t cells, std::string* error) {
  cells_ = cells;
  regions_ = view.count;
  anyFloating_ = view.anyFloating;
  if (failed(region_.upload(view.region, static_cast<size_t>(cells)), error)) return false;
  if (!anyFloating_) return true;
  std::vector<double> inverse(static_cast<size_t>(regions_));
  for (size_t r = 0; r < inverse.size(); ++r)
    inverse[r] = 1.0 / static_cast<double>(std::max<int64_t>(1, view.cellCount[r]));
  return !failed(floating_.upload(view.floating, static_cast<size_t>(regions_)), error) &&
         !failed(inverseCount_.upload(inverse.data(), inverse.size()), error) &&
         !failed(sum_.allocate(static_cast<size_t>(regions_)), error);
}

template <class T>
void DeviceRegionFilter::run(T* values, cudaStream_t stream) {
  if (anyFloating_) {
    cudaMemsetAsync(sum_.get(), 0, static_cast<size_t>(regions_) * sizeof(double), stream);
    regionSumKernel<<<launch::blocks(cells_), launch::kThreads, 0, stream>>>(cells_, region_.get(), floating_.get(),
                                                                             values, sum_.get());
  }
  regionFilterKernel<<<launch::blocks(cells_), launch::kThreads, 0, stream>>>(
      cells_, region_.get(), anyFloating_ ? floating_.get() : nullptr, inverseCount_.get(), sum_.get(), values);
}

void DeviceRegionFilter::apply(float* values, cudaStream_t stream) { run(values, stream); }
void DeviceRegionFilter::apply(double* values, cudaStream_t stream) { run(values, stream); }

struct DeviceMultigrid::Level {
  kernels::PoissonStencil<float> op{};  // device pointers
  DeviceArray<float> cu, cv, cw, diagonal, scale, x, b, r;
  DeviceRegionFilter filter;
  bool filtered = false;  // a coarse level with a floating region
  DeviceArray<kernels::BoundaryCell> boundary;
  DeviceArray<int32_t> reads;
  DeviceArray<float> values, rhs;
  BoundaryLists lists{};
  int64_t cells() const { return op.nx * op.ny * op.nz; }
};

DeviceMultigrid::DeviceMultigrid() = default;
DeviceMultigrid::~DeviceMultigrid() {
  if (exec_) cudaGraphExecDestroy(exec_);
  if (graph_) cudaGraphDestroy(graph_);
}

bool DeviceMultigrid::upload(const PressureSolveView& view, std::string* error) {
  sides_ = view.sides;
  sweeps_ = view.sweeps;
  coarsestSweeps_ = view.coarsestSweeps;
  boundarySweeps_ = view.boundarySweeps;
  size_t scratch = 0;
  for (size_t l = 0; l < view.levels.size(); ++l) {
    const MultigridLevelView& in = view.levels[l];
    auto level = std::make_unique<Level>();
    Level& d = *level;
    const size_t nx = static_cast<size_t>(in.op.nx), ny = static_cast<size_t>(in.op.ny),
                 nz = static_cast<size_t>(in.op.nz), cells = nx * ny * nz;
    if (failed(d.cu.upload(in.op.cu, (nx + 1) * ny * nz), error) ||
        failed(d.cv.upload(in.op.cv, nx * (ny + 1) * nz), error) ||
        failed(d.cw.upload(in.op.cw, nx * ny * (nz + 1)), error) ||
        failed(d.diagonal.upload(in.op.diagonal, cells), error) || failed(d.x.allocate(cells), error) ||
        failed(d.b.allocate(cells), error) || failed(d.r.allocate(cells), error))
      return false;
    if (in.prolongScale && failed(d.scale.upload(in.prolongScale, cells), error)) return false;
    d.op = in.op;
    d.op.cu = d.cu.get();
    d.op.cv = d.cv.get();
    d.op.cw = d.cw.get();
    d.op.diagonal = d.diagonal.get();
    d.op.span = nullptr;
    d.filtered = l > 0 && in.regions.anyFloating;
    if (d.filtered && !d.filter.upload(in.regions, static_cast<int64_t>(cells), error)) return false;
    const int64_t count = in.boundaryCount[0] + in.boundaryCount[1];
    if (count > 0 && boundarySweeps_ > 0) {
      std::vector<kernels::BoundaryCell> both(in.boundary[0], in.boundary[0] + in.boundaryCount[0]);
      both.insert(both.end(), in.boundary[1], in.boundary[1] + in.boundaryCount[1]);
      if (failed(d.boundary.upload(both.data(), both.size()), error) ||
          failed(d.reads.upload(in.boundaryReads, static_cast<size_t>(6 * count)), error) ||
          failed(d.values.allocate(static_cast<size_t>(7 * count)), error) ||
          failed(d.rhs.allocate(static_cast<size_t>(count)), error))
        return false;
    }
    d.lists = BoundaryLists{d.boundary.get(), d.reads.get(), in.boundaryCount[0], count, in.op.nx, in.op.nx * in.op.ny};
    if (l + 1 < view.levels.size()) {
      const kernels::PoissonStencil<float>& next = view.levels[l + 1].op;
      const size_t cx = static_cast<size_t>(next.nx), cy = static_cast<size_t>(next.ny);
      scratch = std::max(scratch, std::max(cx * ny * nz, cx * cy * nz));
    }
    levels_.push_back(std::move(level));
  }
  return !failed(alongX_.allocate(scratch), error) && !failed(alongY_.allocate(scratch), error);
}

void DeviceMultigrid::sweeps(Level& level, int count, bool reverse, cudaStream_t stream) {
  if (level.cells() <= kOneBlockCells) {
    oneBlockSweepsKernel<<<1, kOneBlockThreads, 0, stream>>>(level.op, level.b.get(), level.x.get(), count, reverse);
    return;
  }
  const unsigned blocks = launch::blocks(kernels::colourThreads(level.op));
  for (int sweep = 0; sweep < count; ++sweep)
    for (int half = 0; half < 2; ++half)
      halfSweepKernel<<<blocks, launch::kThreads, 0, stream>>>(level.op, level.b.get(), level.x.get(),
                                                               reverse ? 1 - half : half);
}

void DeviceMultigrid::boundarySweeps(Level& level, bool reverse, cudaStream_t stream) {
  const BoundaryLists& l = level.lists;
  if (l.count == 0 || boundarySweeps_ <= 0) return;
  float* values = level.values.get();
  boundaryGatherKernel<<<launch::blocks(l.count), launch::kThreads, 0, stream>>>(l, level.b.get(), level.x.get(),
                                                                                 values, level.rhs.get());
  if (l.count <= kOneBlockCells) {
    oneBlockBoundarySweepsKernel<<<1, kOneBlockThreads, 0, stream>>>(l, boundarySweeps_, reverse, values,
                                                                     level.rhs.get());
  } else {
    const unsigned blocks = launch::blocks(std::max(l.reds, l.count - l.reds));
    for (int sweep = 0; sweep < boundarySweeps_; ++sweep)
      for (int half = 0; half < 2; ++half)
        boundaryHalfKernel<<<blocks, launch::kThreads, 0, stream>>>(l, reverse ? 1 - half : half, values,
                                                                    level.rhs.get());
  }
  boundaryScatterKernel<<<launch::blocks(l.count), launch::kThreads, 0, stream>>>(l, values, level.x.get());
}

// As the CPU's smoothLevel: pre-smoothing from zero, full sweeps then boundary sweeps; the
// post-smoothing is its adjoint, in reverse order.
void DeviceMultigrid::smoothLevel(Level& level, bool post, cudaStream_t stream) {
  if (!post) {
    cudaMemsetAsync(level.x.get(), 0, static_cast<size_t>(level.cells()) * sizeof(float), stream);
    sweeps(level, sweeps_, false, stream);
  }
  boundarySweeps(level, post, stream);
  if (post) sweeps(level, sweeps_, true, stream);
}

namespace {
kernels::TransferDims dims(const kernels::PoissonStencil<float>& fine, const kernels::PoissonStencil<float>& coarse) {
  return kernels::TransferDims{fine.nx, fine.ny, fine.nz, coarse.nx, coarse.ny, coarse.nz};
}
}  // namespace

void DeviceMultigrid::restrictResidual(Level& fine, Level& coarse, cudaStream_t stream) {
  const kernels::TransferDims d = dims(fine.op, coarse.op);
  residualKernel<<<launch::blocks(fine.cells()), launch::kThreads, 0, stream>>>(fine.op, fine.b.get(), fine.x.get(),
                                                                                fine.r.get());
  restrictXKernel<<<launch::blocks(d.cx * d.ny * d.nz), launch::kThreads, 0, stream>>>(d, sides_, fine.scale.get(),
                                                                                       fine.r.get(), alongX_.get());
  restrictYKernel<<<launch::blocks(d.cx * d.cy * d.nz), launch::kThreads, 0, stream>>>(d, sides_, alongX_.get(),
                                                                                       alongY_.get());
  restrictZKernel<<<launch::blocks(coarse.cells()), launch::kThreads, 0, stream>>>(
      d, sides_, alongY_.get(), coarse.diagonal.get(), coarse.b.get());
}

void DeviceMultigrid::prolongateAdd(Level& fine, Level& coarse, cudaStream_t stream) {
  prolongateKernel<<<launch::blocks(fine.cells()), launch::kThreads, 0, stream>>>(
      dims(fine.op, coarse.op), sides_, fine.scale.get(), coarse.x.get(), fine.x.get());
}

// The CPU's applyPoissonMultigrid, stage for stage.
void DeviceMultigrid::enqueueCycle(const double* r, double* z, cudaStream_t stream) {
  const int last = static_cast<int>(levels_.size()) - 1;
  auto level = [&](int l) -> Level& { return *levels_[static_cast<size_t>(l)]; };
  convertKernel<<<launch::blocks(level(0).cells()), launch::kThreads, 0, stream>>>(level(0).cells(), r,
                                                                                   level(0).b.get());
  for (int l = 0; l < last; ++l) {
    smoothLevel(level(l), false, stream);
    restrictResidual(level(l), level(l + 1), stream);
    if (level(l + 1).filtered) level(l + 1).filter.apply(level(l + 1).b.get(), stream);
  }
  Level& coarsest = level(last);
  cudaMemsetAsync(coarsest.x.get(), 0, static_cast<size_t>(coarsest.cells()) * sizeof(float), stream);
  sweeps(coarsest, coarsestSweeps_, false, stream);
  sweeps(coarsest, coarsestSweeps_, true, stream);
  if (coarsest.filtered) coarsest.filter.apply(coarsest.x.get(), stream);
  for (int l = last - 1; l >= 0; --l) {
    prolongateAdd(level(l), level(l + 1), stream);
    smoothLevel(level(l), true, stream);
    if (level(l).filtered) level(l).filter.apply(level(l).x.get(), stream);
  }
  convertKernel<<<launch::blocks(level(0).cells()), launch::kThreads, 0, stream>>>(level(0).cells(), level(0).x.get(),
                                                                                   z);
}

bool DeviceMultigrid::record(const double* r, double* z, cudaStream_t stream, std::string* error) {
  if (failed(cudaStreamBeginCapture(stream, cudaStreamCaptureModeThreadLocal), error)) return false;
  enqueueCycle(r, z, stream);
  const cudaError_t captured = cudaStreamEndCapture(stream, &graph_);
  return !failed(captured, error) && !failed(cudaGraphInstantiate(&exec_, graph_, 0), error);
}

}  // namespace vp::gpu
