#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang with ASan + UBSan: the fuzz preset) and runs
# each for SECONDS (default 60) from its corpus (tests/fuzz/corpus/<target>). New inputs go to
# build/fuzz/corpus/<target>; a crashing input is written to build/fuzz/crashes/<target>/ and
# fails the run: add it to tests/fuzz/corpus/<target> (which ctest replays) with the fix.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_loader tet_mesh surface_import)
scripts/setup.sh
scripts/build.sh fuzz
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
for t in "${targets[@]}"; do
  work="build/fuzz/corpus/$t" crashes="build/fuzz/crashes/$t"
  mkdir -p "$work" "$crashes"
  echo "fuzz: $t for ${seconds} s" >&2
  # -rss_limit_mb leaves room for a fuzzed scene's grids; -timeout catches hangs.
  "build/fuzz/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 \
    -artifact_prefix="$crashes/" -print_final_stats=1 "$work" "tests/fuzz/corpus/$t" 2>&1 | tail -n 12 >&2
done
