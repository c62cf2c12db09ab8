#!/usr/bin/env bash
# Fresh Debian 12 to a first result: installs, builds, runs the default scenario (the
# chapter-7 identification protocol) and plots it, and installs tcpmsim for this user
# (~/.local: the program in ~/.local/bin, the Python package where python3 finds it, the
# library and its CMake package for find_package(tcpmsim)).
#   results/ch7_identification.h5   the HDF5 record
#   results/ch7_identification.png  power, temperature, deflection and force over time
#   TCPMSIM_PREFIX                  install elsewhere (default ~/.local)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
export CMAKE_GENERATOR="${CMAKE_GENERATOR:-Ninja}"  # new trees only, as scripts/test.sh
prefix="${TCPMSIM_PREFIX:-$HOME/.local}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTCPMSIM_BUILD_TESTS=OFF -DCMAKE_INSTALL_PREFIX="$prefix"
cmake --build build -j"$(nproc)" --target tcpmsim tcpmsim_python
build/tcpmsim run configs/ch7_identification.yaml -o results/ch7_identification.h5
tools/tcpmsim-plot traces results/ch7_identification.h5 -o results/ch7_identification.png
cmake --install build >/dev/null
echo "installed tcpmsim under $prefix (python3 -c 'import tcpmsim')"
