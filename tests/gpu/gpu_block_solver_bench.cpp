// The deformable's linear algebra on a CUDA device against the CPU, on the issues' beam step
// system (beam_step_system.h): 98304 linear tets (the 64x16x16-cell beam, 18785 nodes) and
// about 13000 quadratic tets ("13000q", the 34x8x8-cell beam).
//   BM_GpuSpMV/{bin_bcsr,bcsr,cusparse_bsr}/N   one y = A x between resident vectors:
//       the BIN-BCSR kernel, the plain BCSR kernel (one thread per block row), cuSPARSE's
//       cusparseDbsrmv. Time per product from device events over a batch; counter gbps =
//       the BCSR's bytes (blocks, their column indices, x and y once) per second, the same
//       bytes for all three so the figures compare.
//   BM_GpuCG/{fused,unfused}/98304   block-Jacobi filtered CG to relative residual 1e-6 from
//       zero; time = the iterations on the device; counters iters, ms_per_iter,
//       launches_per_iter, residual.
//   BM_CpuSpMV/N, BM_CpuCG/98304   the same on the CPU (2 worker threads), for the
//       CPU-to-device ratio in the same units.
//   BM_GpuDeformLinearBeam/{cuda,cpu}/N   the beam's 60 steps (beam_run.h) at the actor's default
//       tolerance with its implicit solves on the device (block-Jacobi CG) or on the CPU
//       (the default multigrid), 2 worker threads for everything else; counters hz, tip_dy,
//       cg_iters and the phases' ms per step. cuda_cap2000: the device with the iteration
//       cap raised from the default to 2000 (block-Jacobi needs more iterations than the
//       multigrid; each costs far less).
// Without a device the Gpu benchmarks report "no CUDA device" and stop. Figures: the README's
// GPU section and the commit that adds them.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "beam_run.h"
#include "beam_step_system.h"
#include "cusparse_bsr_multiply.h"
#include "gpu_kernels/device_query.h"
#include "linalg/conjugate_gradient.h"

namespace vp::gpu_test {
namespace {

constexpr int kProductsPerTiming = 200;
constexpr double kCgTolerance = 1e-6;

struct BeamCase {
  BeamStepSystem sys;
  bool ok = false;
  std::string error;
};

// "98304": linear tets of the 4n x n x n beam; "13000q": quadratic, the beam nearest 13000.
BeamCase& beamCase(const std::string& name) {
  static std::map<std::string, std::unique_ptr<BeamCase>> cases;
  std::unique_ptr<BeamCase>& c = cases[name];
  if (c) return *c;
  c = std::make_unique<BeamCase>();
  bench::BeamCells cells;
  const bool quadratic = name.back() == 'q';
  const int64_t tets = std::stoll(name);
  const bool sized = quadratic ? bench::beamCellsNearTetCount(tets, &cells) : bench::beamCellsForTetCount(tets, &cells);
  c->ok = sized && makeBeamStepSystem(cells, quadratic ? 2 : 1, &c->sys);
  if (!c->ok) c->error = sized ? lastError() : "no beam of that size";
  return *c;
}

double bcsrBytes(const BlockSparseMatrix<double>& a) {
  return double(a.blockCount()) * (9 * sizeof(double) + sizeof(int32_t)) + 2.0 * 3 * a.blockRows * sizeof(double);
}

std::unique_ptr<gpu::DeviceBlockSystem> deviceFor(benchmark::State& state, const BeamCase& c) {
  if (!c.ok) {
    state.SkipWithError(c.error.c_str());
    return nullptr;
  }
  if (gpu::cudaDeviceCount() == 0) {
    state.SkipWithError("no CUDA device");
    return nullptr;
  }
  std::string error;
  auto device = gpu::DeviceBlockSystem::create(c.sys.host(true), &error);
  if (!device) state.SkipWithError(error.c_str());
  return device;
}

enum class SpMV { BinBcsr, Bcsr, Cusparse };

// The product the timing will repeat, once on a known x, against the CPU's.
bool sameProductAsCpu(SpMV kind, const BeamCase& c, gpu::DeviceBlockSystem& device, std::string* error) {
  const BlockSparseMatrix<double>& a = c.sys.matrix();
  std::vector<double> x(static_cast<size_t>(c.sys.dofs())), cpu(x.size()), gpu(x.size());
  for (size_t i = 0; i < x.size(); ++i) x[i] = std::cos(0.11 * double(i));
  a.multiply(*c.sys.tasks, x.data(), cpu.data());
  const bool ran = kind == SpMV::Cusparse ? cusparseBsrMultiply(device.bcsr(), x.data(), gpu.data(), error)
                                          : device.multiply(x.data(), gpu.data(), kind == SpMV::Bcsr, error);
  if (!ran) return false;
  double scale = 0, difference = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    scale = std::max(scale, std::abs(cpu[i]));
    difference = std::max(difference, std::abs(gpu[i] - cpu[i]));
  }
  if (difference <= 1e-12 * scale) return true;
  *error = "the device product differs from the CPU's by " + std::to_string(difference / scale);
  return false;
}

void BM_GpuSpMV(benchmark::State& state, SpMV kind, const std::string& beam) {
  BeamCase& c = beamCase(beam);
  auto device = deviceFor(state, c);
  if (!device) return;
  std::string error;
  if (!sameProductAsCpu(kind, c, *device, &error)) return state.SkipWithError(error.c_str());
  double ms = 0;
  for (auto _ : state) {
    const bool ok = kind == SpMV::Cusparse ? timeCusparseBsrMultiply(device->bcsr(), kProductsPerTiming, &ms, &error)
                                           : device->timeMultiply(kProductsPerTiming, kind == SpMV::Bcsr, &ms, &error);
    if (!ok) return state.SkipWithError(error.c_str());
    state.SetIterationTime(ms / 1000.0);
  }
  state.counters["gbps"] = benchmark::Counter(bcsrBytes(c.sys.matrix()) / (ms / 1000.0) / 1e9);
  state.counters["rows"] = c.sys.matrix().blockRows;
  state.counters["blocks"] = double(c.sys.matrix().blockCount());
}

void reportCg(benchmark::State& state, int iterations, double ms, double residual, int launches) {
  state.SetIterationTime(ms / 1000.0);
  state.counters["iters"] = iterations;
  state.counters["ms_per_iter"] = iterations > 0 ? ms / iterations : 0.0;
  state.counters["launches_per_iter"] = iterations > 0 ? double(launches) / iterations : 0.0;
  state.counters["residual"] = residual;
}

void BM_GpuCG(benchmark::State& state, gpu::DeviceCgForm form) {
  BeamCase& c = beamCase("98304");
  auto device = deviceFor(state, c);
  if (!device) return;
  for (auto _ : state) {
    std::vector<double> x(static_cast<size_t>(c.sys.dofs()), 0.0);
    gpu::DeviceCgResult result;
    std::string error;
    if (!device->solve(c.sys.rhs.data(), x.data(), kCgTolerance, 20000, form, &result, &error))
      return state.SkipWithError(error.c_str());
    if (!result.converged) return state.SkipWithError("did not converge");
    reportCg(state, result.iterations, result.deviceMs, result.relativeResidual, result.launches);
  }
}

void BM_CpuSpMV(benchmark::State& state, const std::string& beam) {
  BeamCase& c = beamCase(beam);
  if (!c.ok) return state.SkipWithError(c.error.c_str());
  const BlockSparseMatrix<double>& a = c.sys.matrix();
  std::vector<double> x(static_cast<size_t>(c.sys.dofs()), 1.0), y(x.size());
  for (auto _ : state) {
    a.multiply(*c.sys.tasks, x.data(), y.data());
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["gbps"] =
      benchmark::Counter(bcsrBytes(a) * double(state.iterations()) / 1e9, benchmark::Counter::kIsRate);
}

void BM_CpuCG(benchmark::State& state) {
  BeamCase& c = beamCase("98304");
  if (!c.ok) return state.SkipWithError(c.error.c_str());
  const int64_t n = c.sys.dofs();
  const LinearSystem system = cpuLinearSystem(c.sys);
  CgWorkspace work;
  for (auto _ : state) {
    std::vector<double> x(static_cast<size_t>(n), 0.0);
    const auto start = std::chrono::steady_clock::now();
    const CgResult r = solveConjugateGradient(*c.sys.tasks, system, c.sys.rhs.data(), x.data(),
                                              CgSettings{kCgTolerance, 20000}, Deadline(), work);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!r.converged) return state.SkipWithError("did not converge");
    reportCg(state, r.iterations, ms, r.relativeResidual, 0);
  }
}

void BM_GpuDeformLinearBeam(benchmark::State& state, bool onDevice, int maxIterations) {
  if (onDevice && gpu::cudaDeviceCount() == 0) return state.SkipWithError("no CUDA device");
  for (auto _ : state) {
    const bench::BeamRun run = bench::runBeam(state.range(0), DeformableSolverSettings{}.tolerance, maxIterations, 2,
                                              1, Preconditioner::Auto,
                                              DeformableSolverSettings{}.pMultigridCoarseOperator, onDevice);
    if (!run.ok || run.onDevice != onDevice) return state.SkipWithError("beam setup failed");
    bench::reportBeamRun(state, run);
  }
}

const bool registered = [] {
  const std::pair<SpMV, const char*> kinds[] = {
      {SpMV::BinBcsr, "bin_bcsr"}, {SpMV::Bcsr, "bcsr"}, {SpMV::Cusparse, "cusparse_bsr"}};
  for (const char* beam : {"98304", "13000q"}) {
    for (const auto& [kind, name] : kinds)
      benchmark::RegisterBenchmark((std::string("BM_GpuSpMV/") + name + "/" + beam).c_str(),
                                   [kind = kind, beam = std::string(beam)](benchmark::State& s) {
                                     BM_GpuSpMV(s, kind, beam);
                                   })
          ->UseManualTime()
          ->Unit(benchmark::kMicrosecond)
          ->Iterations(10)
          ->Repetitions(5);
    benchmark::RegisterBenchmark((std::string("BM_CpuSpMV/") + beam).c_str(),
                                 [beam = std::string(beam)](benchmark::State& s) { BM_CpuSpMV(s, beam); })
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime()
        ->Repetitions(5);
  }
  for (const auto& [form, name] : {std::pair{gpu::DeviceCgForm::Fused, "fused"}, {gpu::DeviceCgForm::Unfused, "unfused"}})
    benchmark::RegisterBenchmark((std::string("BM_GpuCG/") + name + "/98304").c_str(),
                                 [form = form](benchmark::State& s) { BM_GpuCG(s, form); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(5);
  const int defaultCap = DeformableSolverSettings{}.maxIterations;
  const std::tuple<bool, int, const char*> beams[] = {
      {true, defaultCap, "cuda"}, {true, 2000, "cuda_cap2000"}, {false, defaultCap, "cpu"}};
  for (const auto& [onDevice, cap, name] : beams)
    benchmark::RegisterBenchmark((std::string("BM_GpuDeformLinearBeam/") + name).c_str(),
                                 [onDevice = onDevice, cap = cap](benchmark::State& s) {
                                   BM_GpuDeformLinearBeam(s, onDevice, cap);
                                 })
        ->Arg(12288)
        ->Arg(98304)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(3);
  benchmark::RegisterBenchmark("BM_CpuCG/98304", BM_CpuCG)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1)
      ->Repetitions(3);
  return true;
}();

}  // namespace
}  // namespace vp::gpu_test
