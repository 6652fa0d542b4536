#!/usr/bin/env bash
# Peer comparison, side by side in one run: dampbench vs scipy's vectorized differential_evolution
# and vs pagmo2 (de, sga, pso_gen, cmaes), on the same data, metric (of_abs), default bounds and budget
# (population × generations × runs). Prints the table and writes it as Markdown (bench/peers/README.md).
#
# usage: bench/peers/run_peers.sh            (from anywhere; root needed only if packages must be installed)
# Environment (defaults in brackets):
#   BUILD_DIR [<repo>/build-peers]  dampbench build dir (configured Release + Ninja if absent)
#   RUNS [50] POP [50] GENS [100] SEED [1]   budget; GENS counts evaluated generations incl. the initial one
#   SCIPY_BW_RUNS [5]   scipy runs on the Bouc–Wen problem (a run takes ~45 s; RUNS=50 would take ~40 min)
#   THREADS [2]         threads for dampbench (--threads) and pagmo2 (thread_bfe / parallel runs)
#   PRECISION [mixed]   dampbench fit --precision: mixed (the population search in float32 lanes, what is
#                       reported in float64) or double
#   ISA [""]            dampbench --isa (sse2, avx2, avx512; empty: the CPU's best), e.g. avx2 on an AVX-512 CPU
#   REPEAT [2]          timed dampbench `fit --runs RUNS` repetitions; the best rate is reported
#   SHORT_S [30] REPEAT_SHORT [5]  a measurement (peer or dampbench) shorter than SHORT_S s is repeated
#                       REPEAT_SHORT times in all, best rate kept
#   ONE_THREAD [1]      also time dampbench with --threads 1
#   BUSY_MAX [0.25]     before each measurement wait until other processes use less than this share of
#   LOAD_WAIT [180]     the cores, for at most LOAD_WAIT s (then measure anyway; load and share are reported)
#   START_WAIT [900]    the same wait, once, before the first measurement
#   PROBLEMS ["fvd bw"] OUT [bench/peers/results/peers.md]
#   PEER_ALGOS ["de ga pso cmaes"]  dampbench optimizers to compare (spaces or commas), each against its peers:
#                       de: scipy differential_evolution and pagmo2 de; ga: pagmo2 sga; pso: pagmo2 pso_gen;
#                       cmaes: pagmo2 cmaes. PEER_ALGOS=cmaes measures only the CMA-ES pair.
#   SKIP_BUILD=1        measure the dampbench binary already in BUILD_DIR
#   NATIVE=1            dampbench built with -DDAMPBENCH_NATIVE=ON in BUILD_DIR/native and the pagmo2 program
#                       with -march=native (table: bench/peers/results/peers-native.md)
#   QUICK=1             smoke test: RUNS=4 GENS=20 SCIPY_BW_RUNS=1 REPEAT=1 LOAD_WAIT=0
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
if [[ "${QUICK:-0}" == 1 ]]; then
  : "${RUNS:=4}" "${GENS:=20}" "${SCIPY_BW_RUNS:=1}" "${REPEAT:=1}" "${LOAD_WAIT:=0}" "${START_WAIT:=0}"
fi
BUILD_DIR="${BUILD_DIR:-$REPO/build-peers}"
RUNS="${RUNS:-50}" POP="${POP:-50}" GENS="${GENS:-100}" SEED="${SEED:-1}"
SCIPY_BW_RUNS="${SCIPY_BW_RUNS:-5}" THREADS="${THREADS:-2}" REPEAT="${REPEAT:-2}" ONE_THREAD="${ONE_THREAD:-1}"
BUSY_MAX="${BUSY_MAX:-0.25}" LOAD_WAIT="${LOAD_WAIT:-180}" START_WAIT="${START_WAIT:-900}"
SHORT_S="${SHORT_S:-30}" REPEAT_SHORT="${REPEAT_SHORT:-5}"
PRECISION="${PRECISION:-mixed}" ISA="${ISA:-}"
PROBLEMS="${PROBLEMS:-fvd bw}"
PEER_ALGOS="${PEER_ALGOS:-de ga pso cmaes}"
PEER_ALGOS="${PEER_ALGOS//,/ }"
if [[ "${NATIVE:-0}" == 1 ]]; then OUT="${OUT:-$HERE/results/peers-native.md}"; else OUT="${OUT:-$HERE/results/peers.md}"; fi
PY=/usr/bin/python3
F=0.5 CR=0.9
FVD_RECORD="$REPO/datasets/fvd/test3_20mm_460mms.csv"
# MR-damper-like Bouc–Wen truth inside the default bounds: z saturates near (A/(β+γ))^(1/n) = 1 mm,
# hysteretic force α·z ≈ 500 N, viscous c0·v ≈ 125 N at the 63 mm/s peak velocity.
BW_PARAMS="c0=2000,k0=1000,x0=0.002,alpha=5e5,beta=3e4,gamma=1e4,A=10,n=1.2"
BW_SINE="amp=0.01,freq=1,cycles=3,fs=500"

log() { echo "[run_peers $(date +%H:%M:%S)] $*" >&2; }
load1() { cut -d' ' -f1 /proc/loadavg; }
# pagmo2's counterpart of each dampbench optimizer (scipy joins de); checked before anything is built.
declare -A PAGMO_ALG=([de]=de [ga]=sga [pso]=pso_gen [cmaes]=cmaes)
for opt in $PEER_ALGOS; do
  [[ -n "${PAGMO_ALG[$opt]:-}" ]] || { log "PEER_ALGOS: unknown optimizer '$opt' (known: de ga pso cmaes)"; exit 1; }
done
[[ -n "${PEER_ALGOS// /}" ]] || { log "PEER_ALGOS is empty (known: de ga pso cmaes)"; exit 1; }

# ---------------------------------------------------------------- dependencies
# dampbench's own build dependencies and the peers' packages, installed with apt-get where missing (a fresh
# machine needs both: scripts/install-deps.sh runs apt-get update first and only when something is missing).
bash "$REPO/scripts/install-deps.sh" python3-numpy python3-scipy libpagmo-dev >&2

# ---------------------------------------------------------------- builds
# NATIVE=1: dampbench with -DDAMPBENCH_NATIVE=ON (-march=native) in $BUILD_DIR/native, the pagmo2 program
# with -march=native; the default is the portable x86-64 build.
DB_BUILD="$BUILD_DIR" native_flags=() PAGMO_BUILD="$BUILD_DIR/pagmo-peer"
if [[ "${NATIVE:-0}" == 1 ]]; then
  DB_BUILD="$BUILD_DIR/native" PAGMO_BUILD="$BUILD_DIR/pagmo-peer-native"
  native_flags=(-DCMAKE_CXX_FLAGS=-march=native)
fi
if [[ ! -f "$DB_BUILD/build.ninja" ]]; then
  cmake -S "$REPO" -B "$DB_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBENCH_NATIVE="${NATIVE:-0}" >&2
fi
DB="$DB_BUILD/dampbench"
if [[ "${SKIP_BUILD:-0}" != 1 ]]; then
  log "building dampbench in $DB_BUILD"
  if ! ninja -C "$DB_BUILD" dampbench >&2; then
    # The work tree may be mid-edit by others; an earlier binary still measures the engine.
    [[ -x "$DB" ]] || { log "dampbench build failed"; exit 1; }
    log "WARNING: dampbench build failed; measuring the existing $DB ($(date -r "$DB" +%F\ %T))"
  fi
fi
cmake -S "$HERE/pagmo" -B "$PAGMO_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release "${native_flags[@]}" >&2
ninja -C "$PAGMO_BUILD" >&2
PG="$PAGMO_BUILD/pagmo_peer"

# ---------------------------------------------------------------- data, bounds, sub-step rule
WORK="$BUILD_DIR/peers-data"
mkdir -p "$WORK" "$(dirname "$OUT")"
RESULTS="$WORK/results.jsonl"
: >"$RESULTS"
bounds() {  # bounds MODEL DATA lower|upper -> comma list in dampbench's parameter order: the box `fit` searches on
  # that record (the model's defaults scaled to the record: mrd.bouc_wen's are, fvd's are not), from fit's JSON
  "$DB" fit --model "$1" --data "$2" --metric of_abs --optimizer de --pop 4 --iters 2 --runs 2 --budget fixed \
    --format json | "$PY" -c 'import json,sys; b=json.load(sys.stdin)["bounds"][sys.argv[1]]
print(",".join(repr(float(v)) for v in b.values()))' "$3"
}
# The Bouc–Wen sub-step rule's constant, read from the model so the peers follow it.
SUBSTEPS=$(sed -n '/^struct BoucWen/,/^};/p' "$REPO/models/mrd.cpp" | sed -n 's/.*kSubstepsPerStroke = \([0-9.e+]*\);.*/\1/p')
[[ -n "$SUBSTEPS" ]] || { log "cannot read BoucWen::kSubstepsPerStroke from models/mrd.cpp"; exit 1; }

# fvd: the committed record as dampbench fit reads it; the peers get dampbench's own prepared signals
# (simulate --input prints t, x, v, a after unit conversion and engine/record/differentiate.cpp) plus F in N.
mkdir -p "$WORK/fvd"
"$DB" simulate --model fvd.linear_viscous --params m=0,C=0 --input "$FVD_RECORD" -o "$WORK/fvd/signals.csv"
"$PY" "$HERE/merge_force.py" "$WORK/fvd/signals.csv" "$FVD_RECORD" "$WORK/fvd/$(basename "$FVD_RECORD")"
# bw: a synthetic record; dampbench fit reads its v and a columns as they are, so both sides share it.
mkdir -p "$WORK/bw"
"$DB" simulate --model mrd.bouc_wen --params "$BW_PARAMS" --sine "$BW_SINE" --noise-rel 0.01 --seed 1 \
  -o "$WORK/bw/bw_sine_10mm_1hz.csv"

declare -A MODEL=([fvd]=fvd.gv_linear_elastic [bw]=mrd.bouc_wen)
declare -A DB_DATA=([fvd]="$FVD_RECORD" [bw]="$WORK/bw/bw_sine_10mm_1hz.csv")
declare -A PEER_DATA=([fvd]="$WORK/fvd/$(basename "$FVD_RECORD")" [bw]="$WORK/bw/bw_sine_10mm_1hz.csv")

# Check that the peers' input is bit-for-bit what dampbench uses: fitting the merged file (same stem, so the
# same random streams) must give the same results as fitting the record. Left out: the paths, the timings and
# the operating variables, which fit reads from the record's "# operating:" comment and estimates from the
# signals for the merged file, which has no comments (scipy's reader would take one for its header).
check_fit() { "$DB" fit --model fvd.gv_linear_elastic --data "$1" --optimizer de --pop 20 --iters 10 --runs 2 \
  --format json | "$PY" -c 'import json,sys
j = json.load(sys.stdin)
for k in ("data", "operating", "wall_time_s", "candidate_samples_per_s"): del j[k]
print(json.dumps(j, indent=1))'; }
if [[ "$(check_fit "$FVD_RECORD")" != "$(check_fit "${PEER_DATA[fvd]}")" ]]; then
  log "the merged fvd signals differ from what dampbench fit reads"; exit 1
fi
log "peer input for fvd is bit-identical to dampbench's prepared signals"

# ---------------------------------------------------------------- measurement helpers
cpu_busy() {  # fraction of all cores busy over 3 s, from /proc/stat (0..1)
  local a b
  a=($(head -1 /proc/stat)); sleep 3; b=($(head -1 /proc/stat))
  awk -v u="$(( (b[1]+b[2]+b[3]+b[6]+b[7]) - (a[1]+a[2]+a[3]+a[6]+a[7]) ))" \
      -v i="$(( (b[4]+b[5]) - (a[4]+a[5]) ))" 'BEGIN{printf "%.2f", ((u+i) > 0 ? u/(u+i) : 0)}'
}
# Waits (at most LOAD_WAIT s) until the machine is quiet: other processes use less than BUSY_MAX of the
# cores. The CPU share is used rather than the load average, which our own previous measurement inflates
# for a minute or more. Both are recorded.
wait_quiet() {
  local start=$SECONDS busy
  busy=$(cpu_busy)
  while awk -v b="$busy" -v m="$BUSY_MAX" 'BEGIN{exit !(b >= m)}' && ((SECONDS - start < LOAD_WAIT)); do
    sleep 7
    busy=$(cpu_busy)
  done
  QUIET_BUSY=$busy
  echo "{\"peer\": \"load\", \"load1\": $(load1), \"busy\": $busy, \"when\": \"$(date +%T)\"}" >>"$RESULTS"
}
# Runs a peer command that prints one JSON line (one algorithm); adds the load readings. A measurement
# shorter than SHORT_S seconds is repeated up to REPEAT_SHORT times in all and the best rate kept, as for
# dampbench (the final metrics are those of the first repetition).
peer() {
  local before after rep=0 tmp="$WORK/peer.out"
  : >"$tmp"
  while :; do
    wait_quiet
    before=$(load1)
    "$@" >>"$tmp"
    after=$(load1)
    echo "{\"peer\": \"load\", \"load1\": $after, \"when\": \"$(date +%T)\"}" >>"$RESULTS"
    rep=$((rep + 1))
    local wall
    wall=$(tail -1 "$tmp" | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["wall_time_s"])')
    if ! awk -v w="$wall" -v s="$SHORT_S" 'BEGIN{exit !(w < s)}' || ((rep >= REPEAT_SHORT)); then break; fi
  done
  "$PY" -c 'import json,sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
d = rows[0]
d["rates"] = [r["candidate_samples_per_s"] for r in rows]
d["candidate_samples_per_s"] = max(d["rates"])
d["cpu_rates"] = [r["candidate_samples_per_cpu_s"] for r in rows]
d.update(load_before=float(sys.argv[2]), load_after=float(sys.argv[3]), busy_before=float(sys.argv[4]))
print(json.dumps(d))' "$tmp" "$before" "$after" "$QUIET_BUSY" >>"$RESULTS"
}
# cpu_run OUT CPU CMD...: runs CMD with stdout to OUT and writes its user and system CPU seconds to CPU.
cpu_run() {
  "$PY" -c 'import resource, subprocess, sys
with open(sys.argv[1], "w") as out:
    r = subprocess.run(sys.argv[3:], stdout=out)
u = resource.getrusage(resource.RUSAGE_CHILDREN)
open(sys.argv[2], "w").write(f"{u.ru_utime} {u.ru_stime}\n")
sys.exit(r.returncode)' "$@"
}
# dampbench: REPEAT timed fits with --runs RUNS (the rate), one with --threads 1, and RUNS single-run fits
# over seeds SEED..SEED+RUNS-1 for the distribution of final metrics (fit's JSON gives best/worst/mean/std only).
ours() {
  local prob=$1 opt=$2 rates=() cpu_rates=() rate1=null loads=()
  local args=(fit --model "${MODEL[$prob]}" --data "${DB_DATA[$prob]}" --metric of_abs --optimizer "$opt"
              --pop "$POP" --iters "$GENS" --precision "$PRECISION" --format json ${ISA:+--isa "$ISA"})
  local n=$REPEAT wall
  for ((i = 0; i < n; i++)); do
    wait_quiet
    loads+=("$QUIET_BUSY/$(load1)")
    cpu_run "$WORK/fit.json" "$WORK/fit.cpu" "$DB" "${args[@]}" --runs "$RUNS" --seed "$SEED" --threads "$THREADS"
    rates+=("$("$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["candidate_samples_per_s"])' "$WORK/fit.json")")
    # candidate-samples per CPU second (user + system of the whole process, start-up included)
    cpu_rates+=("$("$PY" -c 'import json,sys
j = json.load(open(sys.argv[1])); u, s = map(float, open(sys.argv[2]).read().split()[-2:])
print(j["evaluations"] * j["samples"] / (u + s) if u + s > 0 else "nan")' "$WORK/fit.json" "$WORK/fit.cpu")")
    wall=$("$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["wall_time_s"])' "$WORK/fit.json")
    if awk -v w="$wall" -v s="$SHORT_S" 'BEGIN{exit !(w < s)}' && ((n < REPEAT_SHORT)); then n=$REPEAT_SHORT; fi
  done
  cp "$WORK/fit.json" "$WORK/fit_${prob}_${opt}.json"
  if [[ "$ONE_THREAD" == 1 ]]; then
    wait_quiet
    rate1=$("$DB" "${args[@]}" --runs "$RUNS" --seed "$SEED" --threads 1 |
      "$PY" -c 'import json,sys; print(json.load(sys.stdin)["candidate_samples_per_s"])')
  fi
  local values="$WORK/values_${prob}_${opt}.txt"
  : >"$values"
  for ((s = SEED; s < SEED + RUNS; s++)); do
    "$DB" "${args[@]}" --runs 1 --seed "$s" --threads "$THREADS" |
      "$PY" -c 'import json,sys; print(json.load(sys.stdin)["runs"]["best"])' >>"$values"
  done
  "$PY" - "$prob" "$opt" "$WORK/fit_${prob}_${opt}.json" "$values" "$rate1" "${loads[*]}" "${cpu_rates[*]}" "${rates[@]}" >>"$RESULTS" <<'EOF'
import json, statistics, sys
prob, opt, fit_path, values_path, rate1, loads, cpu_rates, *rates = sys.argv[1:]
fit = json.load(open(fit_path))
vals = [float(v) for v in open(values_path) if v.strip()]
print(json.dumps({"peer": "dampbench", "problem": prob, "algorithm": opt, "rates": [float(r) for r in rates],
                  "rate_1thread": float(rate1) if rate1 != "null" else float("nan"),
                  "best": min(vals), "median": statistics.median(vals), "worst": max(vals), "values": vals,
                  "cpu_rates": [float(r) for r in cpu_rates.split()],
                  "timed_runs": fit["runs"], "evaluations": fit["evaluations"],
                  "busy_load_before": [[float(x) for x in l.split("/")] for l in loads.split()]}))
EOF
  log "dampbench $prob $opt: rates ${rates[*]} (1 thread: $rate1)"
}

# ---------------------------------------------------------------- the comparison
if ((START_WAIT > 0)); then
  log "waiting up to $START_WAIT s for a quiet machine (others' CPU share < $BUSY_MAX)"
  LOAD_WAIT=$START_WAIT wait_quiet
fi
log "start: load average $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores; budget pop $POP × $GENS generations × $RUNS runs; optimizers: $PEER_ALGOS"
for prob in $PROBLEMS; do
  lo=$(bounds "${MODEL[$prob]}" "${DB_DATA[$prob]}" lower)
  hi=$(bounds "${MODEL[$prob]}" "${DB_DATA[$prob]}" upper)
  common=(--problem "$prob" --data "${PEER_DATA[$prob]}" --lower "$lo" --upper "$hi" --pop "$POP" --gens "$GENS"
          --seed "$SEED" --substeps-per-stroke "$SUBSTEPS")
  scipy_runs=$RUNS
  [[ $prob == bw ]] && scipy_runs=$SCIPY_BW_RUNS
  # Each peer measurement is followed at once by dampbench's timed fits of the matching optimizer, so the
  # two sides of a ratio see the same machine state as far as possible.
  for opt in $PEER_ALGOS; do
    if [[ $opt == de ]]; then
      log "$prob: scipy differential_evolution ($scipy_runs runs)"
      peer "$PY" "$HERE/scipy_peer.py" "${common[@]}" --F "$F" --CR "$CR" --runs "$scipy_runs"
    fi
    palg=${PAGMO_ALG[$opt]}
    log "$prob: pagmo2 $palg ($RUNS runs, $THREADS threads)"
    peer "$PG" "${common[@]}" --F "$F" --CR "$CR" --runs "$RUNS" --threads "$THREADS" --algorithms "$palg"
    log "$prob: dampbench $opt"
    ours "$prob" "$opt"
  done
done

cpu=$(sed -n 's/^model name\s*:\s*//p' /proc/cpuinfo | head -1)
header="## dampbench vs peers — $(date -u +'%Y-%m-%d %H:%M UTC')

Budget: population $POP × $GENS generations (initial one included) × $RUNS runs (scipy on bw: $SCIPY_BW_RUNS runs); \
metric of_abs; dampbench default bounds; optimizers: $PEER_ALGOS; DE rand/1/bin F = $F, CR = $CR; CMA-ES λ = $POP, σ₀ = 0.3 of each range \
(dampbench ipop restarts, its default; pagmo2 cmaes without restarts, ftol = xtol = 0, force_bounds). dampbench $(git -C "$REPO" describe --always --dirty 2>/dev/null || echo "?") \
built Release ($([[ "${NATIVE:-0}" == 1 ]] && echo "DAMPBENCH_NATIVE=ON, -march=native; pagmo2 program -march=native too" || echo "portable x86-64, no -march=native")), --threads $THREADS, --precision $PRECISION, vector kernels ${ISA:-of the CPU (its best)}; pagmo2 $(dpkg-query -W -f='${Version}' libpagmo-dev 2>/dev/null) on $THREADS threads; \
scipy $("$PY" -c 'import scipy; print(scipy.__version__)'), numpy $("$PY" -c 'import numpy; print(numpy.__version__)'). \
CPU: $cpu, $(nproc) cores. Candidate-samples/s = evaluations × samples / wall time."
header+="
Script settings: RUNS=$RUNS POP=$POP GENS=$GENS SEED=$SEED PRECISION=$PRECISION ISA=${ISA:-} PEER_ALGOS=\"$PEER_ALGOS\" SCIPY_BW_RUNS=$SCIPY_BW_RUNS THREADS=$THREADS REPEAT=$REPEAT \
SHORT_S=$SHORT_S REPEAT_SHORT=$REPEAT_SHORT ONE_THREAD=$ONE_THREAD BUSY_MAX=$BUSY_MAX LOAD_WAIT=$LOAD_WAIT START_WAIT=$START_WAIT \
SKIP_BUILD=${SKIP_BUILD:-0} (dampbench binary built $(date -r "$DB" +'%F %T'))."
"$PY" "$HERE/make_table.py" "$RESULTS" --out "$OUT" --header "$header" \
  --repeat "$REPEAT" --repeat-short "$REPEAT_SHORT" --short-s "$SHORT_S"
cp "$RESULTS" "${OUT%.md}.jsonl"
log "table written to $OUT (raw measurements: ${OUT%.md}.jsonl)"
