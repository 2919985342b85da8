#!/usr/bin/env bash
# The GPU checks, on a machine with a CUDA device: the gpu-labelled tests and the GPU
# benchmarks (JSON), from an already-built tree.
# Usage: gpu_check.sh BUILD_DIR OUT_DIR [LIB_DIR] [BENCHMARK_FILTER (default BM_Gpu)]
# LIB_DIR holds shared libraries the binaries need that the machine lacks (a device machine
# lent without this project's Debian packages).
set -uo pipefail
build="${1:?build dir}"; out="${2:?out dir}"; libs="${3:-}"; filter="${4:-BM_Gpu}"
mkdir -p "$out"
[ -n "$libs" ] && export LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
if ldd "$build/tests/gpu/vp_gpu_benchmarks" | grep -q "libcusparse.*not found"; then
  # cuSPARSE from the machine's CUDA toolkit or Python wheels, wherever it is.
  dir=$(dirname "$(find / -name 'libcusparse.so.12' -not -path '*/proc/*' 2>/dev/null | head -1)")
  export LD_LIBRARY_PATH="$dir:$LD_LIBRARY_PATH"
fi
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,memory.total --format=csv | tee "$out/device.txt"
"$build/tests/gpu/vp_gpu_tests" 2>&1 | tee "$out/gpu_tests.txt"
tests=$?
"$build/tests/gpu/vp_gpu_benchmarks" --benchmark_filter="$filter" --benchmark_out="$out/gpu_bench.json" \
  --benchmark_out_format=json 2>&1 | tee "$out/gpu_bench.txt"
bench=$?
echo "gpu_check: tests exit $tests, benchmarks exit $bench"
[ "$tests" -eq 0 ] && [ "$bench" -eq 0 ]
