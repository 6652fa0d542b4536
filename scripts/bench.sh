#!/usr/bin/env bash
# Performance benchmarks (docs/performance.md): builds the portable and the native build, then runs
# `dampbench bench` (JSON into results/bench/) and the Google Benchmark suite for both.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
mkdir -p results/bench
for variant in portable native; do
  native=OFF; [ "$variant" = native ] && native=ON
  cmake -S . -B "build-$variant" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBENCH_NATIVE=$native -DDAMPBENCH_BUILD_TESTS=OFF
  cmake --build "build-$variant" --parallel "$(nproc)" --target dampbench bench_models
  "./build-$variant/dampbench" bench --format json > "results/bench/bench_$variant.json"
  "./build-$variant/bench/bench_models" --benchmark_format=json --benchmark_out="results/bench/models_$variant.json" \
    --benchmark_filter="${BENCH_FILTER:-samples:2048}" > /dev/null
  echo "results/bench/bench_$variant.json, results/bench/models_$variant.json"
done
