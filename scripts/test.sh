#!/usr/bin/env bash
# The whole test suite: set up, build a preset (default release; also debug, asan), run ctest.
# The tsan preset builds and runs only the threading tests (label threads).
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
scripts/setup.sh
scripts/build.sh "$preset"
ctest --preset "$preset" -j "$(nproc)"
