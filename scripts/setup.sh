#!/usr/bin/env bash
# Installs (with apt, non-interactively) whatever VolPhys needs that is missing. Idempotent:
# when everything is present it installs nothing and needs no root.
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config binutils
  libeigen3-dev libbullet-dev libassimp-dev nlohmann-json3-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  python3-numpy
  # pip install of bindings/python (setuptools as its build backend, no network)
  python3-pip python3-setuptools python3-wheel
  # sample host: offscreen snapshots (OSMesa), PNG (stb), viewer (GLFW) under Xvfb + Mesa
  libosmesa6-dev libstb-dev libgl-dev libglfw3-dev xvfb xauth libgl1-mesa-dri
  # sample host: smoke and level-set volumes as OpenVDB grids (--export-volumes vdb); OpenVDB's
  # CMake find module also wants Boost.Iostreams, which Debian's package does not pull in
  libopenvdb-dev libboost-iostreams-dev
  # plots (Python example, output checks) and the C# bindings
  python3-matplotlib python3-pil mono-mcs mono-runtime
  # the default scene's jelly: /usr/share/assimp/models/Collada/duck.dae (a box without it)
  assimp-testmodels
  # the asan preset and the fuzz targets (scripts/fuzz.sh): clang, libFuzzer, sanitizer runtimes
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present" >&2
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
