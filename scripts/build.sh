#!/usr/bin/env bash
# Configures and builds one CMake preset (release, debug, asan). Usage: build.sh [PRESET] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
shift || true
cmake --preset "$preset" >&2
if [ $# -gt 0 ]; then
  cmake --build --preset "$preset" --target "$@" >&2
else
  cmake --build --preset "$preset" >&2
fi
