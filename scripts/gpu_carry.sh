#!/usr/bin/env bash
# Packs what the GPU checks need on a lent device machine (which has CUDA but none of this
# project's Debian packages) into one folder: the gpu test and benchmark binaries of an
# already-built tree, the shared libraries they load that are not part of the base system,
# gpu_check.sh, and run.sh, which runs the checks there:
#   scripts/gpu_carry.sh [BUILD_DIR (build/release)] [OUT (.devcarry)]
# then, with OUT (ignored by git: .gitignore) named in the device tool's carry:
#   bash .devcarry/run.sh ['BENCHMARK_FILTER']     (results under $OUT on that machine)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/release}"
out="${2:-.devcarry}"
bins=("$build/tests/gpu/vp_gpu_tests" "$build/tests/gpu/vp_gpu_benchmarks")
for b in "${bins[@]}"; do [ -x "$b" ] || { echo "gpu_carry: $b is not built (CUDA path off?)" >&2; exit 1; }; done
rm -rf "$out" && mkdir -p "$out/build/tests/gpu" "$out/lib"
cp "${bins[@]}" "$out/build/tests/gpu/"
cp scripts/gpu_check.sh "$out/"
# Libraries from this project's packages (Bullet, assimp and what it pulls in, Google
# Benchmark); glibc, libstdc++ and the CUDA libraries are the device machine's own.
ldd "${bins[@]}" | awk '/=> \// {print $3}' | sort -u |
  grep -Ev '/(libc|libm|libdl|librt|libpthread|libgcc_s|libstdc\+\+|ld-linux[^/]*|libcu[a-z]*|libnvJitLink)\.so' |
  while read -r lib; do cp -L "$lib" "$out/lib/"; done
cat > "$out/run.sh" <<'RUN'
#!/usr/bin/env bash
# On the device machine: the gpu tests and benchmarks (gpu_check.sh), results under $OUT.
cd "$(dirname "$0")"
./gpu_check.sh build "${OUT:-out}" "$PWD/lib" "${1:-BM_Gpu}"
RUN
chmod +x "$out/run.sh"
du -sh "$out" >&2
