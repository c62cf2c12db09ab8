#!/usr/bin/env bash
# The command line's whole fits and discover on the chapter-7 bench (simulated): their exit codes,
# summaries and files. Apart from test_cli.sh, whose error paths are quick, because these are
# most of the command line's time (28 of 32 s in Release, about 190 s under ASan): the sanitizer
# tree leaves this test out (.ci/run), while its fit and discover tests run the same code.
# Usage: test_cli_whole_runs.sh TCPMSIM_BINARY SOURCE_DIR
set -uo pipefail
tcpmsim=$1
source_dir=$2
source "$(dirname "$0")/cli_support.sh"

discover="$source_dir/configs/discover"
expect 0 "the chapter-7 bench writes a measurement" -- "$tcpmsim" run "$discover/ch7_protocol.yaml" -o "$work/bench.h5" --quiet
expect 0 "measure reads the model with the bench's instruments" -- "$tcpmsim" measure "$discover/ch7_base.yaml" \
  --set "measurement.file=$work/bench.h5" --bench "$discover/ch7_bench.yaml" -o "$work/measured.csv" --quiet
expect 0 "fit takes the synthetic measurement" -- "$tcpmsim" fit "$discover/ch7_fit.yaml" --data "$work/measured.csv" \
  --out "$work/fit_measured" --set 'multistart.starts=0' --jobs 2 --quiet
expect 0 "fit writes its report" -- "$tcpmsim" fit "$discover/ch7_fit.yaml" --data "$work/bench.h5" --out "$work/fit" \
  --set 'multistart.starts=0' --jobs 2
contains "$work/out" "muscle.mechanics.k1" "the summary lists the parameters"
contains "$work/out" "validation     force" "the summary scores the validation window"
[[ -s $work/fit/fit.json && -s $work/fit/fitted.yaml && -s $work/fit/fit.h5 ]] && echo "ok: fit.json, fitted.yaml, fit.h5" || { echo "FAIL: fit outputs missing"; failures=$((failures + 1)); }
expect 0 "the fitted scenario runs as it is" -- "$tcpmsim" run "$work/fit/fitted.yaml" -o "$work/fitted.h5" --quiet
# A verdict has its exit code (0 an effect, 10 none, 11 unexplained), and a picture that cannot
# be drawn is a warning: an installed copy whose plot tool fails still exits with the verdict.
mkdir -p "$work/installed"
cp "$tcpmsim" "$work/installed/tcpmsim"
printf '#!/bin/sh\necho "no plotting here" >&2\nexit 1\n' >"$work/installed/tcpmsim-plot"
chmod +x "$work/installed/tcpmsim-plot"
expect 10 "discover on data the base model fits to the noise says none (exit 10)" -- \
  "$work/installed/tcpmsim" discover --model "$discover/ch7_base.yaml" --data "$work/measured.csv" \
  --inputs power,deflection --outputs force --validate-from 400 --effects viscoelastic_relaxation \
  --starts 2 --min-signature 3.5 --alias-correlation 0.95 --despike-all --out "$work/discover_none"
contains "$work/out" "verdict: none (the base model fits to the noise floor)" "the verdict is printed"
contains "$work/err" "warning: the plots of $work/discover_none could not be drawn" "a failed picture is a warning"
contains "$work/discover_none/discovery.json" '"verdict_kind": "none"' "discovery.json carries the verdict's kind"
contains "$work/discover_none/discovery.json" '"min_signature": 3.5' "the settings record the signature's bar"
contains "$work/discover_none/discovery.json" '"alias_correlation": 0.95' "the settings record the aliases' correlation"
contains "$work/discover_none/discovery.json" '"despike_all": true' "the settings record what was despiked"

check_provenance
echo "$failures failure(s)"
exit $((failures > 0))
