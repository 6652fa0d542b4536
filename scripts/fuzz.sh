#!/usr/bin/env bash
# Fuzzing: builds the libFuzzer targets of tests/fuzz in the sanitizer build (scripts/sanitizer-build.sh: clang,
# AddressSanitizer and UBSan on all of dampbench's code they reach) and runs each for FUZZ_SECONDS (default 60) from
# seed corpora made of the repository's records, sweep files, law strings, a real store and its groups as MPI
# messages. Fails on the first crash, sanitizer finding, timeout (10 s per input) or out-of-memory; the input that did
# it is kept in build-asan/fuzz/findings/<target>/ (copy it to tests/fuzz/regressions/<target>/ and it is replayed by
# every later run).
# Usage: bash scripts/fuzz.sh [target ...]   (default: every target)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
seconds="${FUZZ_SECONDS:-60}"
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(fuzz_record fuzz_sweep_spec fuzz_laws fuzz_key_values fuzz_store fuzz_group_message)
# The sanitizer build (scripts/sanitizer-build.sh) holds the targets: the test suite's build, where scripts/test.sh has
# already built them.
bash scripts/sanitizer-build.sh "${targets[@]}"

# Seed corpora: what the tests and presets read.
corpus=build-asan/fuzz/corpus
rm -rf "$corpus" && mkdir -p "$corpus"/{fuzz_record,fuzz_sweep_spec,fuzz_laws,fuzz_key_values,fuzz_store,fuzz_group_message}
for f in datasets/fvd/*.csv docs/examples/*.txt; do  # the first byte picks the loader options
  for option in 0 1 3; do { printf "\\$(printf %03o $option)"; head -c 20000 "$f"; } > "$corpus/fuzz_record/$option-$(basename "$f")"; done
done
# a rig export read as channels: the mapping, gains and events split (56), with smoothing, mean removal and whole cycles (249)
for option in 8 56 249; do
  { printf "\\$(printf %03o $option)"; head -c 20000 docs/examples/rig_export.txt; } > "$corpus/fuzz_record/$option-rig_export.txt"
done
# a MATLAB v5 file of a simulated record (t, x, v, a, F), read with its own names (0) and with a matrix mapping (16)
"${DAMPBENCH:-./build/dampbench}" simulate --model mrd.bingham --params f_c=500,c0=2000,f0=0 \
  --sine amp=0.01,freq=1,cycles=1,fs=100 -o build-asan/fuzz/seed.mat
for option in 0 16; do
  { printf "\\$(printf %03o $option)"; cat build-asan/fuzz/seed.mat; } > "$corpus/fuzz_record/$option-seed.mat"
done
cp datasets/presets/*.toml docs/examples/*.toml "$corpus/fuzz_sweep_spec/"
for f in datasets/papers/*.toml; do cp "$f" "$corpus/fuzz_sweep_spec/paper_$(basename "$f")"; done  # (names as presets')
i=0
for law in "c0=poly(I,1);alpha=poly(I,2);k0=poly(I,1)" "A=prod(poly(I,2),poly(amp,1),poly(freq,1))" "c=power(w)" \
           "k=gauss2(w)" "n=0.9929;c_r=poly(phi,3)" "x=free"; do
  printf '%s' "$law" > "$corpus/fuzz_laws/$((i++))"
done
for kv in "m=300,C=8.2e5,alpha=0.3,K1=4e6" "pc=0.6,pm=0.03" "t,x,v,F" "x=mm,v=mm/s,F=kN" "1.5e-3" "+2" \
          "amp=0.02,vpeak=0.46,cycles=3,fs=1000"; do
  printf '%s' "$kv" > "$corpus/fuzz_key_values/$((i++))"
done
store_seed=build-asan/fuzz/seed-store
rm -rf "$store_seed"
"${DAMPBENCH:-./build/dampbench}" run docs/examples/quick.toml -o "$store_seed" --quiet --no-report > /dev/null
cp "$store_seed/store.sqlite" "$corpus/fuzz_store/quick.sqlite"
# fuzz_group_message writes the store's groups, encoded as MPI messages, into its corpus when it starts.
export DAMPBENCH_FUZZ_SEED_STORE="$PWD/$store_seed/store.sqlite" DAMPBENCH_FUZZ_SEED_DIR="$PWD/$corpus/fuzz_group_message"

# One fuzzer per core at a time: each libFuzzer process is single-threaded, so the targets share the cores
# instead of queueing, and each still gets its full FUZZ_SECONDS.
fuzz_one() {
  local t="$1"
  mkdir -p "build-asan/fuzz/findings/$t"
  local dirs=("$corpus/$t")
  [ -d "tests/fuzz/regressions/$t" ] && dirs+=("tests/fuzz/regressions/$t")
  # Inputs up to 64 kB, or the largest seed's size: a seed cut short (a whole store is about 150 kB) would only ever
  # reach the fuzzer damaged.
  local max_len largest
  largest=$(find "${dirs[@]}" -type f -printf '%s\n' | sort -n | tail -1)
  max_len=$((largest > 65536 ? largest : 65536))
  ASAN_OPTIONS=detect_leaks=1 "./build-asan/tests/fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="$max_len" -print_final_stats=1 -artifact_prefix="build-asan/fuzz/findings/$t/" "${dirs[@]}" \
    > "build-asan/fuzz/findings/$t.log" 2>&1
}
jobs="${FUZZ_JOBS:-$(nproc)}"
failed=0
for ((first = 0; first < ${#targets[@]}; first += jobs)); do
  batch=("${targets[@]:first:jobs}")
  pids=()
  for t in "${batch[@]}"; do
    echo "== $t: ${seconds} s"
    fuzz_one "$t" & pids+=($!)
  done
  for i in "${!batch[@]}"; do
    t="${batch[$i]}"
    status=0
    wait "${pids[$i]}" || status=$?
    log="build-asan/fuzz/findings/$t.log"
    echo "-- $t"
    grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss_mb)" "$log" || true
    if [ "$status" -ne 0 ]; then
      tail -40 "$log" >&2
      echo "fuzz: $t failed (exit $status); the input is in build-asan/fuzz/findings/$t/" >&2
      failed=1
    fi
  done
  [ "$failed" -eq 0 ] || exit 1
done
echo "fuzz: ${#targets[@]} targets, ${seconds} s each (${jobs} at a time), no crash"
