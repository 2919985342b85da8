#!/usr/bin/env bash
# The main job: set up, build (Release), and run the sample host on its default scene,
# headless. Extra arguments go to the host (see build/release/sample_host/volphys_host --help).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh release volphys_host
exec build/release/sample_host/volphys_host --out out/sample "$@"
