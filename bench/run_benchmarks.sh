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
echo "== a 1000 s closed-loop task (deflection sweep, PID through the estimator), targets 2 s switched, 50 ms averaged"
task=configs/ch7_control/deflection_sweep.yaml
for fidelity in switched averaged; do
  echo "$fidelity BDF, hard stops at every edge and sample: $("$build_dir/bench/bench_integration" $task 3 "scenario.duration=1000 s" drive.fidelity=$fidelity)"
done
echo "naive, non-stiff Adams, averaged 1000 s: $("$build_dir/bench/bench_integration" $task 3 "scenario.duration=1000 s" drive.fidelity=averaged solver.method=adams)"
echo "naive, non-stiff Adams, switched 0.5 s only (the 0.1 us electrical time constant bounds its steps): $("$build_dir/bench/bench_integration" $task 1 "scenario.duration=0.5 s" drive.fidelity=switched solver.method=adams)"
