#!/usr/bin/env bash
# Installs dampbench's build and test dependencies from Debian 12 packages (run as root); extra package
# names given as arguments are installed too (scripts/bench.sh adds libsleef-dev).
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libtbb-dev libsundials-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libtomlplusplus-dev libfmt-dev nlohmann-json3-dev libsqlite3-dev libnlopt-cxx-dev
  libmatio-dev        # MATLAB .mat records (engine/record/mat_file.cpp); brings zlib1g-dev and libhdf5-dev
  libjs-d3            # D3, inlined into HTML reports (engine/report)
  chromium python3    # the report test renders a report in headless Chromium (tests/e2e/report_browser_test.py)
  clang libclang-rt-14-dev  # libFuzzer for scripts/fuzz.sh (tests/fuzz)
  libopenmpi-dev openmpi-bin  # mpirun -np K dampbench run (engine/distributed; tests/e2e/mpi_test.py)
  python3-dev pybind11-dev python3-numpy python3-pandas python3-pytest  # the Python module (python/) and its tests
  python3-scipy python3-h5py  # the tests' .mat files: v5 written with scipy.io, v7.3 with h5py
  python3-matplotlib  # the plot of docs/python.md's session, which tests/python/test_docs.py runs
  "$@"
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
