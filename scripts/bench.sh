#!/usr/bin/env bash
# Performance benchmarks (docs/performance.md). Three builds: portable (the default build: any x86-64, kernels
# at the CPU's best vector level), native (-march=native) and native with SLEEF instead of glibc's libmvec.
# Into results/bench/, per build:
#   bench_<variant>.json    `dampbench bench --format json` (portable: also bench_portable-sse2.json and
#                           bench_portable-avx2.json, the same build at the lower vector levels, --isa)
#   models_<variant>.json   Google Benchmark: every model at 2 048 samples, and the vector-function probes
#                           (SLEEF build: the probes only)
#   growth_<variant>.*      fvd.gv_linear_elastic and mrd.bouc_wen over candidates × samples × threads:
#                           JSON, Markdown tables (.md) and cost_growth_<variant>.svg (portable, native)
# Takes about 20 minutes on 2 cores (2026-11-24, Zen 5: 19 min); run it on an idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh libsleef-dev
mkdir -p results/bench
for variant in portable native native-sleef; do
  native=OFF; [ "$variant" != portable ] && native=ON
  math=libmvec; [ "$variant" = native-sleef ] && math=sleef
  cmake -S . -B "build-$variant" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBENCH_NATIVE=$native \
    -DDAMPBENCH_VECTOR_MATH=$math -DDAMPBENCH_BUILD_TESTS=OFF
  cmake --build "build-$variant" --parallel "$(nproc)" --target dampbench bench_models
  "./build-$variant/dampbench" bench --format json > "results/bench/bench_$variant.json"
  echo "results/bench/bench_$variant.json"
  if [ "$variant" = portable ]; then
    # The default build at each lower vector level this CPU has (engine/kernels/isa.hpp): bench_portable-<isa>.json
    for isa in sse2 avx2; do  # a level this CPU lacks is refused (exit 2) and skipped
      if json="$("./build-$variant/dampbench" --isa "$isa" bench --format json)"; then
        echo "$json" > "results/bench/bench_$variant-$isa.json"
        echo "results/bench/bench_$variant-$isa.json"
      fi
    done
  fi
  filter="${BENCH_FILTER:-samples:2048/|^vector/}"
  [ "$variant" = native-sleef ] && filter="^vector/"
  "./build-$variant/bench/bench_models" --benchmark_format=json --benchmark_out="results/bench/models_$variant.json" \
    --benchmark_filter="$filter" > /dev/null
  echo "results/bench/models_$variant.json"
  [ "$variant" = native-sleef ] && continue
  "./build-$variant/bench/bench_models" --benchmark_format=json --benchmark_out="results/bench/growth_$variant.json" \
    --benchmark_filter='evaluate/(fvd.gv_linear_elastic|mrd.bouc_wen)/' > /dev/null
  /usr/bin/python3 bench/cost_growth.py "results/bench/growth_$variant.json" \
    --svg "results/bench/cost_growth_$variant.svg" > "results/bench/growth_$variant.md"
  echo "results/bench/growth_$variant.{json,md}, results/bench/cost_growth_$variant.svg"
done
