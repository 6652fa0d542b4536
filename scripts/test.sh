#!/usr/bin/env bash
# The test command (CI runs it through .ci/run): installs dependencies, builds everything (library, command
# line, tests, benchmarks) and runs the whole test suite through ctest; then the hardening stages:
#   - the test suite again under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan), without the tests
#     listed in SANITIZER_SKIP below (they re-run long optimizations that the release run already covers; mpi
#     runs OpenMPI, whose own allocations LeakSanitizer would report; bouc_wen_benchmark fits twice), and with
#     readme_examples skipping the README's real-data fits (DAMPBENCH_README_SKIP_REAL_DATA);
#   - every libFuzzer target for FUZZ_SECONDS (default 30 here, 60 when scripts/fuzz.sh runs alone) each, one
#     target per core at a time (scripts/fuzz.sh, build-fuzz).
# The sanitizer and fuzz builds compile the lane kernels once, at the baseline vector level (DAMPBENCH_ISA_DISPATCH
# OFF; the release suite runs every level the CPU has), with line tables only (-g1), and the sanitizer build
# compiles the test and command files at -O1: compiling is where the time of this command goes. Tests that
# compare two levels skip under the sanitizers, as in a native build.
# DAMPBENCH_QUICK=1 stops after the release test suite. Tests that need ../shared/data skip with a message when
# it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)"
ctest --test-dir build --output-on-failure --timeout 900 -j "$(nproc)"
[ "${DAMPBENCH_QUICK:-0}" = 1 ] && exit 0

echo "== sanitizers (ASan + UBSan)"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDAMPBENCH_SANITIZE=ON -DDAMPBENCH_BUILD_BENCH=OFF \
  -DDAMPBENCH_ISA_DISPATCH=OFF
cmake --build build-asan --parallel "$(nproc)"
SANITIZER_SKIP="${SANITIZER_SKIP:-store_soak|RealData|Utfsm|ModelRecovery|StandardFunctions|Conformance|bouc_wen_ga_lm|^mpi$|^bouc_wen_benchmark$}"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 DAMPBENCH_README_SKIP_REAL_DATA=1 \
  ctest --test-dir build-asan --output-on-failure --timeout 900 -j "$(nproc)" -E "$SANITIZER_SKIP"

echo "== fuzzing"
FUZZ_SECONDS="${FUZZ_SECONDS:-30}" bash scripts/fuzz.sh
