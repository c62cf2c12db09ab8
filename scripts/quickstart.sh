#!/usr/bin/env bash
# Fresh Debian 12 to a first result: installs, builds, runs the default scenario (the
# chapter-7 identification protocol) and plots it.
#   results/ch7_identification.h5   the HDF5 record
#   results/ch7_identification.png  power, temperature, deflection and force over time
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTCPMSIM_BUILD_TESTS=OFF
cmake --build build -j"$(nproc)" --target tcpmsim
build/tcpmsim run configs/ch7_identification.yaml -o results/ch7_identification.h5
tools/tcpmsim-plot traces results/ch7_identification.h5 -o results/ch7_identification.png
