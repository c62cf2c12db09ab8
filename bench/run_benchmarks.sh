#!/usr/bin/env bash
# Runs every benchmark against a Release build and prints the figures. No assertions.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${TCPMSIM_BENCH_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j"$(nproc)" --target tcpmsim bench_integration bench_maxwell bench_spring_forces \
  bench_cvode_restart_floor bench_assembly >/dev/null
echo "== assembling n trivial components: wiring by name and ordering (target: 10 000 in < 1 s, growth ~n)"
"$build_dir/bench/bench_assembly"
# The default scenario's integration against the engine before the composition refactor (the
# run context, the registry): the same benchmark built from that commit, timed in turn with ours.
reference=${TCPMSIM_REFERENCE_COMMIT:-a5ee02a}
if git cat-file -e "$reference^{commit}" 2>/dev/null; then
  echo "== default scenario against commit $reference's engine (target: no more than 5 % slower)"
  reference_dir=build-reference
  rm -rf "$reference_dir/source"
  mkdir -p "$reference_dir/source"
  git archive "$reference" | tar -x -C "$reference_dir/source"
  cmake -S "$reference_dir/source" -B "$reference_dir/build" -DCMAKE_BUILD_TYPE=Release -DTCPMSIM_BUILD_TESTS=OFF >/dev/null
  cmake --build "$reference_dir/build" -j"$(nproc)" --target bench_integration >/dev/null
  /usr/bin/python3 bench/compare_with_commit.py "$build_dir/bench/bench_integration" \
    "$reference_dir/build/bench/bench_integration" configs/ch7_identification.yaml 7
else
  echo "== (commit $reference is not in this clone: no comparison with the earlier engine)"
fi
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
echo "non-stiff Adams, averaged 1000 s (without the current the loop is not stiff, and Adams needs no Jacobian): $("$build_dir/bench/bench_integration" $task 3 "scenario.duration=1000 s" drive.fidelity=averaged solver.method=adams)"
echo "the naive choice for the switched drive, non-stiff Adams, 0.5 s only (the 0.1 us electrical time constant bounds its steps): $("$build_dir/bench/bench_integration" $task 1 "scenario.duration=0.5 s" drive.fidelity=switched solver.method=adams)"
echo "the floor, bare CVODE on the same two states restarted at every 20 Hz sample (no components, no outputs):"
for method in bdf adams; do
  echo "  $method: $("$build_dir/bench/bench_cvode_restart_floor" $method 1000 5)"
done
echo "== bundles of 1 to 1000 muscles on their own Muscle Drives, sparse against dense (targets: KLU exponent <= 1.1, 1000 muscles x 100 s < 10 s, linear memory)"
/usr/bin/python3 bench/bench_bundle_scaling.py "$build_dir" bench/bundle_scaling.yaml
echo "== sweeps: throughput on 1 and 2 threads and under mpirun -n 2, per-run overhead, record compression (targets: parallel efficiency >= 90 %, overhead < 5 %, record within 2x of integration)"
/usr/bin/python3 bench/bench_sweep.py "$build_dir"
echo "== fit of the six force-model parameters on 620 s of 16 Hz data (target < 5 s)"
/usr/bin/python3 bench/bench_fit.py "$build_dir"
echo "== discover over the whole effect catalogue on 620 s of 16 Hz data (target < 2 min)"
/usr/bin/python3 bench/bench_discover.py "$build_dir"
