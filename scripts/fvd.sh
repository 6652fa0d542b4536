#!/usr/bin/env bash
# The main job: installs dependencies, builds dampbench for this machine's CPU (-DDAMPBENCH_NATIVE=ON:
# the default build stays portable to any x86-64, this one uses AVX2/AVX-512 when present) and runs the
# fvd preset; tables go to results/fvd. Extra arguments go to `dampbench run` (e.g. --threads 2).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-native -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBENCH_NATIVE=ON -DDAMPBENCH_BUILD_TESTS=OFF
cmake --build build-native --parallel "$(nproc)" --target dampbench
./build-native/dampbench run datasets/presets/fvd.toml -o results/fvd --fresh "$@"
