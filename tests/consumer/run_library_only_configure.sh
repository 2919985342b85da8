#!/usr/bin/env bash
# Configures the source tree as a library-only build, with every package that only the sample
# host, the tests or the bindings use made unfindable: the configure must succeed and generate
# the library and nothing else. Usage: run_library_only_configure.sh SOURCE_DIR
set -euo pipefail
source="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake -S "$source" -B "$work" -G Ninja --no-warn-unused-cli \
  -DVOLPHYS_BUILD_SAMPLES=OFF -DVOLPHYS_BUILD_TESTS=OFF -DVOLPHYS_BUILD_CSHARP=OFF -DVOLPHYS_CUDA=OFF \
  -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_glfw3=ON -DCMAKE_DISABLE_FIND_PACKAGE_OpenGL=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON -DCMAKE_DISABLE_FIND_PACKAGE_OpenVDB=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_CUDAToolkit=ON > "$work/configure.log"
targets="$(ninja -C "$work" -t targets all)"
grep -q '^volphys: ' <<<"$targets" || { echo "library-only: no volphys target"; exit 1; }
for t in volphys_host volphys_viewer volphys_csharp vp_unit_tests vp_benchmarks; do
  if grep -q "^$t: " <<<"$targets"; then echo "library-only: unexpected target $t"; exit 1; fi
done
echo "library-only: configured with only the library's dependencies"
