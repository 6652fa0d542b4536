#!/usr/bin/env bash
# Installs dependencies, builds everything (library, command line, tests, benchmarks) and runs the
# whole test suite through ctest. Tests that need ../shared/data skip with a message when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)"
ctest --test-dir build --output-on-failure --timeout 900 -j "$(nproc)"
