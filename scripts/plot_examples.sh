#!/usr/bin/env bash
# One picture of each kind tcpmsim-plot draws, from runs made here: the README's pictures
# (scripts/plot_examples.sh docs/images) and CI's check that the plotting package works on a
# fresh machine (scripts/plot_examples.sh results/plots). Needs a build in build/.
#   traces   the default scenario                          ch7_identification.png
#   steps    the force step task, rise-time marks           steps_force.png
#   bode     the force sweep task's Bode plot (control-tasks)  bode_force.png
#   sweep    the CI sweep's bandwidth over hA x C and tau against C   sweep_bandwidth.png, sweep_time_constant.png
#   bundle   the 19-muscle bundle's temperature spread      bundle_temperature_spread.png
#   discovery  discover on data with a hidden hysteresis: residuals before and after, and the
#            diagnostic                                     discover_residuals.png, discover_diagnostic.png
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs/images}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
plot=tools/tcpmsim-plot
build/tcpmsim run configs/ch7_identification.yaml -q -o "$work/identification.h5"
$plot traces "$work/identification.h5" -o "$out/ch7_identification.png"
build/tcpmsim run configs/ch7_control/force_steps.yaml -q -o "$work/force_steps.h5"
$plot steps "$work/force_steps.h5" --reference controller/reference --response load/force \
  -o "$out/steps_force.png"
build/tcpmsim control-tasks configs/ch7_control/force_sweep.yaml -q -o "$work/tasks.h5"
$plot bode "$work/tasks.h5" --task ch7_force_sweep -o "$out/bode_force.png"
build/tcpmsim sweep configs/sweeps/thermal_hA_C.yaml --jobs 2 -q -o "$work/sweep.h5"
$plot sweep "$work/sweep.h5" --x muscle.thermal.conductance --y muscle.thermal.heat_capacity \
  --metric force_bandwidth -o "$out/sweep_bandwidth.png"
$plot sweep "$work/sweep.h5" --x muscle.thermal.heat_capacity --metric time_constant --colour muscle.thermal.conductance \
  -o "$out/sweep_time_constant.png"
build/tcpmsim run configs/bundle/hexagonal_parallel.yaml -q -o "$work/bundle.h5"
$plot bundle "$work/bundle.h5" --bundle bundle --time 149 -o "$out/bundle_temperature_spread.png"
build/tcpmsim run configs/discover/ch7_protocol.yaml -q -o "$work/protocol.h5"
build/tcpmsim measure configs/discover/ch7_base.yaml --set "measurement.file=$work/protocol.h5" \
  --set 'muscle.effects=[{type: hysteresis, stiffness: 50 N/m, force: 6 mN}]' \
  --bench configs/discover/ch7_bench.yaml -q -o "$work/hidden_hysteresis.csv"
build/tcpmsim discover --model configs/discover/ch7_base.yaml --data "$work/hidden_hysteresis.csv" \
  --inputs power,deflection --outputs force --validate-from 400 \
  --effects hysteresis,slow_relaxation,viscoelastic_relaxation --max-order 1 --jobs 2 --no-plots -q \
  --out "$work/discover"
$plot discovery "$work/discover" -o "$work/discover"
cp "$work/discover/residuals.png" "$out/discover_residuals.png"
cp "$work/discover/diagnostic.png" "$out/discover_diagnostic.png"
