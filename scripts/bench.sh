#!/usr/bin/env bash
# Builds the Release benchmarks and runs them: JSON on stdout, progress on stderr.
# Usage: scripts/bench.sh [FILTER]   (FILTER is a Google Benchmark regex)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh release vp_benchmarks
filter="${1:-.}"
exec build/release/tests/bench/vp_benchmarks --benchmark_filter="$filter" --benchmark_format=json \
  --benchmark_out=/dev/stderr --benchmark_out_format=console
