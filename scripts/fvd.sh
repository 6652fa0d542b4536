#!/usr/bin/env bash
# The main job: installs dependencies, builds dampbench (the default build, the same one scripts/test.sh
# makes: it runs the model kernels at the best vector level of this CPU, AVX-512, AVX2 or SSE2) and runs the
# fvd preset; tables go to results/fvd. Extra arguments go to `dampbench run` (e.g. --threads 2).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target dampbench
./build/dampbench run datasets/presets/fvd.toml -o results/fvd --fresh "$@"
