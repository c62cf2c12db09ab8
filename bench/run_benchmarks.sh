#!/usr/bin/env bash
# Runs every benchmark against a Release build and prints the figures. No assertions.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${TCPMSIM_BENCH_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j"$(nproc)" --target tcpmsim bench_integration bench_maxwell bench_spring_forces >/dev/null
echo "== default scenario against SciPy (issue: >= 100x at equal accuracy)"
/usr/bin/python3 bench/bench_default_scenario.py "$build_dir" configs/ch7_identification.yaml
echo "== Maxwell's sum over 52 non-uniform windings (target < 50 us)"
"$build_dir/bench/bench_maxwell"
echo "== the ten Table 4.2 simulations (target < 2 s)"
"$build_dir/bench/bench_spring_forces" configs/ch4
