#!/usr/bin/env bash
# The sanitizer build (build-asan), shared by the sanitizer test suite (scripts/test.sh) and the fuzz targets
# (scripts/fuzz.sh): clang with AddressSanitizer + UndefinedBehaviorSanitizer on every target and the fuzzer's
# coverage on the libraries that read the fuzzers' input (top-level CMakeLists.txt, dampbench_fuzz_coverage), so the
# library is compiled once for both. The lane kernels are compiled once, at the baseline vector level
# (DAMPBENCH_ISA_DISPATCH=OFF; the release suite runs every level the CPU has); no benchmarks.
# Usage: bash scripts/sanitizer-build.sh [target ...]   (default: every target)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=build-asan
# A folder configured with another compiler (GCC, as this build used to be) is configured afresh.
if [ -f "$dir/CMakeCache.txt" ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang++' "$dir/CMakeCache.txt"; then
  rm -rf "$dir"
fi
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DDAMPBENCH_SANITIZE=ON -DDAMPBENCH_FUZZ=ON -DDAMPBENCH_BUILD_BENCH=OFF -DDAMPBENCH_ISA_DISPATCH=OFF > /dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$dir" --parallel "$(nproc)" "${targets[@]}"
