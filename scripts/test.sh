#!/usr/bin/env bash
# The test command (CI runs it through .ci/run): installs dependencies, builds everything (library, command
# line, tests, benchmarks) and runs the whole test suite through ctest; then the hardening stages:
#   - the test suite again under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan, clang), without the tests
#     listed in SANITIZER_SKIP below. Under the sanitizers a fit runs 20-30 times slower than in the release build
#     (no vector lanes, a check on every access), so the suite leaves to the release run the tests that repeat at
#     full budget what a shorter test in the same suite runs under the sanitizers: what an optimization reaches
#     (recovery of known parameters and of the true law families, standard functions, the fit's defaults on a
#     Spencer record), repeats at a larger size (LS-SVM tuning on larger rows) and the long end-to-end runs of the
#     executable (the README's commands, held-out fits beside per-file fits, the fit report's held-out plots, a
#     sweep choosing laws against `fit --laws auto`, kill-and-resume, three shards merged, the verdicts and figures
#     of the papers', neutral-truth and real-data protocol presets and the README's Results from them, the UTFSM
#     per-file table of docs/reproduce.md (fits at the avx2 level, which the sanitizer build does not run), the building
#     and inverse figures of docs/examples.md from full El Centro runs, the report's page in Chromium (its sweep
#     and held-out fits are the sanitized part: the Cli report tests run the report's files); the shorter
#     HeldOut*, LawSelection*, ExeSweep*, Merge*, store and report tests run the same library files). mpi runs OpenMPI, whose
#     own allocations LeakSanitizer would report; bouc_wen_benchmark fits twice. docs/performance.md checks that
#     every library file still runs;
#   - every libFuzzer target for FUZZ_SECONDS (default 30 here, 60 when scripts/fuzz.sh runs alone) each, one
#     target per core at a time (scripts/fuzz.sh). The fuzz targets are part of the sanitizer build
#     (scripts/sanitizer-build.sh): the library is compiled once for the sanitizer suite and the fuzzers.
# Every build compiles its targets' files in unity batches (DAMPBENCH_UNITY_BUILD). The sanitizer build compiles
# the lane kernels once, at the baseline vector level (DAMPBENCH_ISA_DISPATCH OFF; the release suite runs every
# level the CPU has), with line tables only (-g1), and compiles the test and command files at -O1: compiling is
# where most of this command's time goes. Tests that compare two levels skip under the sanitizers, as in a native
# build.
# At the end (and when a stage fails) it prints each stage's wall time and CPU time (user + system of the stage's
# processes), so a change that adds minutes shows in CI's log; docs/performance.md keeps the measured table.
# DAMPBENCH_QUICK=1 stops after the release test suite. Tests that need ../shared/data skip with a message when
# it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

stage_rows=()
builds=()
cpu_ticks() {  # user + system clock ticks of this shell's waited-for children (fields 16 and 17 of /proc/PID/stat)
  local stat
  stat=$(< "/proc/$$/stat")
  stat=${stat##*) }  # past the command name, which may hold spaces
  read -r -a fields <<< "$stat"
  echo $((fields[13] + fields[14]))
}
# stage NAME COMMAND...: runs COMMAND and keeps its wall and CPU seconds for the table.
stage() {
  local name="$1" start ticks status=0
  shift
  echo "== $name"
  start=$(date +%s%N)
  ticks=$(cpu_ticks)
  "$@" || status=$?
  stage_rows+=("$(printf '| %-26s | %8d | %8d |' "$name" "$(( ($(date +%s%N) - start) / 1000000000 ))" \
                  "$(( ($(cpu_ticks) - ticks) / $(getconf CLK_TCK) ))")")
  return "$status"
}
print_stages() {
  [ ${#stage_rows[@]} -gt 0 ] || return 0
  echo
  local cpu
  cpu="$(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1), family $(sed -n 's/^cpu family\s*: //p' /proc/cpuinfo | head -1)"
  cpu+=" model $(sed -n 's/^model\s*: //p' /proc/cpuinfo | head -1)$(grep -q avx512f /proc/cpuinfo && echo ', AVX-512')"
  echo "Stage times on $(nproc) cores of $cpu:"
  printf '| %-26s | %8s | %8s |\n|%s|%s|%s|\n' stage "wall s" "CPU s" "$(printf -- '-%.0s' {1..28})" "---------:" "---------:"
  printf '%s\n' "${stage_rows[@]}"
  echo "total wall: $((SECONDS / 60)) min $((SECONDS % 60)) s"
  local build
  for build in "${builds[@]}"; do  # the heaviest compile steps and slowest tests of each build this run made
    [ -f "$build/.ninja_log" ] && /usr/bin/python3 scripts/build_times.py "$build" --top 5 || true
  done
}
trap print_stages EXIT

stage "install dependencies" bash scripts/install-deps.sh
builds+=(build)
stage "release build" bash -c 'cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null &&
                               cmake --build build --parallel "$(nproc)"'
stage "release ctest" ctest --test-dir build --output-on-failure --timeout 900 -j "$(nproc)"
[ "${DAMPBENCH_QUICK:-0}" = 1 ] && exit 0

skip="store_soak|RealData|Utfsm|ModelRecovery|StandardFunctions|Conformance|bouc_wen_ga_lm|FitDefaultsRecover|OnLargerRows|^mpi$"
skip+="|^bouc_wen_benchmark$|LawSelection.PicksTheTrueFamilies|^readme_examples$|HeldOutCommand.ReferenceIsTheBaseModel|HeldOutCommand.ARecordPredictedWithout"
skip+="|FitReportDrawsEachHeldOutRecord|SweepLawsAuto.AGroupChoosesTheTrueLaws|ExeSweep.InterruptedAndKilled|Merge.ThreeShards"
skip+="|VaryingCommand.FitRecovers|FvdPresetWritesItsReproduction|^paper_claims_|^readme_results$|^utfsm_table$|^report_in_browser$|ControlCli.ExamplesBuildingTableIsTheCommandsOutput"
SANITIZER_SKIP="${SANITIZER_SKIP:-$skip}"
builds+=(build-asan)
stage "sanitizer build" bash scripts/sanitizer-build.sh
stage "sanitizer ctest" env ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure --timeout 900 -j "$(nproc)" -E "$SANITIZER_SKIP"

stage "fuzzing" env FUZZ_SECONDS="${FUZZ_SECONDS:-30}" bash scripts/fuzz.sh
