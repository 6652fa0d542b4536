#!/usr/bin/env bash
# Optimizer benchmark on dampbench's own damper problems (damper_problems.toml says which and how the best known
# is set): runs the sweep, writes its HTML report and prints the fixed-target runtime tables (success, ERT in
# evaluations and in seconds, per optimizer and problem) as Markdown. A benchmark, not a test: the full run
# takes long (docs/performance.md); QUICK=1 is the smoke test.
#
# usage: bench/optimizers/run.sh            (from anywhere)
# Environment (defaults in brackets):
#   BUILD_DIR [<repo>/build]   the dampbench binary is BUILD_DIR/dampbench (build it first)
#   OUT [bench/optimizers/results/damper_problems, QUICK: .../quick]   output folder: the sweep files' copies,
#                              the Kwok record, store.sqlite, the tables of each part, report.html, runtime.md
#   THREADS [every core]       dampbench run --threads
#   TARGET_REL [0.001]         runtime target: best known + TARGET_REL × |best known| (the sweep files' tables
#                              use 0.001 too)
#   FRESH=1                    start the store over (default: resume it, or start it when absent)
#   PARTS [algebraic ode]      the parts to run (damper_problems.toml's include list is rewritten to them):
#                              the ODE part takes hours on 2 cores
#   QUICK=1                    smoke test: every optimizer entry at population 8 × 4 iterations (the -x10
#                              reference entries 8 × 40), 2 runs, on the Kwok record, fvd test 1 and the UTFSM
#                              record 5mm3Hz0x5A only
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
QUICK="${QUICK:-0}"
BUILD_DIR="${BUILD_DIR:-$REPO/build}"
if [[ "$QUICK" == 1 ]]; then OUT="${OUT:-$HERE/results/quick}"; else OUT="${OUT:-$HERE/results/damper_problems}"; fi
TARGET_REL="${TARGET_REL:-0.001}"
DAMPBENCH="$BUILD_DIR/dampbench"
[[ -x "$DAMPBENCH" ]] || { echo "run.sh: no dampbench binary at $DAMPBENCH: build it first (cmake --build $BUILD_DIR)" >&2; exit 2; }
log() { echo "[optimizers $(date +%H:%M:%S)] $*" >&2; }
mkdir -p "$OUT"

# ---------------------------------------------------------------- the sweep files
# Copied beside the Kwok record they name. QUICK rewrites the copies: a fixed tiny budget in every
# [[optimizers]] entry (10 × the iterations for the -x10 reference entries), 2 runs, fewer records.
quick_budget() {
  awk '
    function flush() {
      if (entry) { print "population = 8"; print "iterations = " (x10 ? 40 : 4); print "" }
      entry = 0; x10 = 0
    }
    /^\[\[optimizers\]\]/ { flush(); entry = 1; print; next }
    /^\[/ { flush(); print; next }
    entry && /^(population|iterations)[ ]*=/ { next }
    entry && /^label[ ]*=[ ]*".*-x10"/ { x10 = 1 }
    /^runs[ ]*=/ { print "runs = 2"; next }
    { print }
    END { flush() }'
}
# Replaces the line $2 of file $1 by $3; fails when the line is not there, so that an edit of the sweep file
# cannot silently make QUICK run everything.
replace_line() {
  grep -qxF -- "$2" "$1" || { echo "run.sh: line '$2' not found in $1" >&2; exit 2; }
  awk -v from="$2" -v to="$3" '$0 == from { print to; next } { print }' "$1" > "$1.tmp" && mv "$1.tmp" "$1"
}
for f in damper_problems.toml algebraic.toml ode.toml; do
  if [[ "$QUICK" == 1 && "$f" != damper_problems.toml ]]; then quick_budget < "$HERE/$f" > "$OUT/$f"; else cp "$HERE/$f" "$OUT/$f"; fi
done
PARTS="${PARTS:-algebraic ode}"
parts_list=""
for p in $PARTS; do
  [[ "$p" == algebraic || "$p" == ode ]] || { echo "run.sh: PARTS: unknown part '$p' (known: algebraic, ode)" >&2; exit 2; }
  parts_list+="${parts_list:+, }\"$p.toml\""
done
replace_line "$OUT/damper_problems.toml" 'include = ["algebraic.toml", "ode.toml"]' "include = [$parts_list]"
if [[ "$QUICK" == 1 ]]; then
  replace_line "$OUT/algebraic.toml" 'glob = "@generated/fvd/test*.csv"' 'glob = "@generated/fvd/test1*.csv"'
  replace_line "$OUT/ode.toml" \
    'files = ["@shared/utfsm-mr-damper/10mm1Hz1A.txt", "@shared/utfsm-mr-damper/5mm3Hz0x5A.txt", "@shared/utfsm-mr-damper/25mm0x25Hz0A.txt"]' \
    'files = ["@shared/utfsm-mr-damper/5mm3Hz0x5A.txt"]'
fi

# ---------------------------------------------------------------- the noisy Kwok record
# The two-frequency record of tests/test_support.hpp (two_sine_record: 300 samples at 250 Hz, x, v and a exact),
# its force simulated by crfd.kwok at the parameters of tests/unit/models/test_model_recovery.cpp, plus Gaussian
# noise of 0.5 % of the force RMS (seed 11).
awk 'BEGIN {
  pi = atan2(0, -1); X1 = 0.015; w1 = 2 * pi * 1.5; X2 = 0.006; w2 = 2 * pi * 4.1; phase = 0.3
  print "t,x,v,a"
  for (k = 0; k < 300; ++k) {
    t = k / 250.0
    printf "%.17g,%.17g,%.17g,%.17g\n", t, X1 * sin(w1 * t) + X2 * sin(w2 * t + phase),
      X1 * w1 * cos(w1 * t) + X2 * w2 * cos(w2 * t + phase), -X1 * w1 * w1 * sin(w1 * t) - X2 * w2 * w2 * sin(w2 * t + phase)
  }
}' > "$OUT/two_sine.csv"
"$DAMPBENCH" simulate --model crfd.kwok --params c_r=3,k_r=25,eta=0.5,mu=6,xi=0.8,T_r=0.011 \
  --input "$OUT/two_sine.csv" --noise-rel 0.005 --seed 11 -o "$OUT/kwok_noisy.csv"

# ---------------------------------------------------------------- run, report, tables
run_args=(-o "$OUT" --quiet --no-report)
[[ -n "${THREADS:-}" ]] && run_args+=(--threads "$THREADS")
[[ "${FRESH:-0}" == 1 ]] && run_args+=(--fresh)
log "dampbench run $OUT/damper_problems.toml ${run_args[*]}"
start=$SECONDS
"$DAMPBENCH" run "$OUT/damper_problems.toml" "${run_args[@]}" > "$OUT/run.log"
log "run: $((SECONDS - start)) s (tables of each part in $OUT/<part>/, log in $OUT/run.log)"
"$DAMPBENCH" report "$OUT/store.sqlite" -o "$OUT/report.html" >&2
"$DAMPBENCH" table "$OUT/store.sqlite" --kind runtime --target-rel "$TARGET_REL" --format md | tee "$OUT/runtime.md"
log "runtime tables: $OUT/runtime.md; report: $OUT/report.html"
