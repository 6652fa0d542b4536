#!/usr/bin/env bash
# Installs dependencies, builds dampbench and runs the fvd preset (the main job): tables go to results/fvd.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target dampbench
./build/dampbench run datasets/presets/fvd.toml -o results/fvd "$@"
