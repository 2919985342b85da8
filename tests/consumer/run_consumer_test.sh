#!/usr/bin/env bash
# Installs the built VolPhys into a temporary prefix, then builds and runs tests/consumer/main.c
# against it twice: through find_package(volphys CONFIG) and through pkg-config; and runs the
# installed sample host where it was built.
# Usage: run_consumer_test.sh BUILD_DIR SOURCE_DIR C_COMPILER [EXTRA_C_FLAGS [EXTRA_LINK_FLAGS]]
# (a sanitizer build's flags and its compiler, so the consumer loads the instrumented library
# with the same sanitizer runtime.)
set -euo pipefail
build="$1" source="$2" cc="$3" flags="${4:-}" link_flags="${5:-}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
libdir="$(dirname "$(find "$work/prefix" -name 'libvolphys.so' | head -1)")"

cmake -S "$source/tests/consumer" -B "$work/cmake-build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_C_COMPILER="$cc" -DCMAKE_C_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags $link_flags" \
  > "$work/configure.log"
cmake --build "$work/cmake-build" > "$work/build.log"
LD_LIBRARY_PATH="$libdir" "$work/cmake-build/consumer"

export PKG_CONFIG_PATH="$libdir/pkgconfig"
# shellcheck disable=SC2046,SC2086  # pkg-config's output is a list of flags
"$cc" -std=c99 -pedantic-errors $flags $link_flags "$source/tests/consumer/main.c" -o "$work/pkg-consumer" \
  $(pkg-config --cflags --libs volphys)
LD_LIBRARY_PATH="$libdir" "$work/pkg-consumer"

# The installed sample host finds the installed library (its RPATH) and the installed scenes.
host="$work/prefix/bin/volphys_host"
if [ -x "$host" ]; then
  "$host" --scene "$work/prefix/share/volphys/scenes/default.json" --frames 2 --quiet --snapshot-every 0 \
    --export-every 0 --out "$work/host-out" > "$work/host.log"
  grep -q "summary: 2 frames" "$work/host.log"
  echo "consumer: the installed host ran"
fi
echo "consumer: both builds ran against $work/prefix"
