#!/usr/bin/env bash
# Runs every benchmark against a Release build and prints the figures. No assertions.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${TCPMSIM_BENCH_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j"$(nproc)" --target tcpmsim bench_integration >/dev/null
/usr/bin/python3 bench/bench_default_scenario.py "$build_dir" configs/ch7_identification.yaml
