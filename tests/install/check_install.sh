#!/usr/bin/env bash
# The installed tree serves another project: `cmake --install` the build into a scratch prefix,
# build tests/install/external against it with find_package(tcpmsim), run a scenario through
# it, and require its record to equal, dataset by dataset, the installed program's (but for the
# command line, which only the program knows); the
# installed Python package must import from the prefix alone.
# Usage: check_install.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$(realpath "$1") source=$(realpath "$2") python=$3
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
prefix=$scratch/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
for installed in bin/tcpmsim include/tcpmsim/sim/scenario.h include/tcpmsim/tcpmsim/version.h \
  lib/cmake/tcpmsim/tcpmsimConfig.cmake lib/libtcpmsim_engine.a; do
  test -e "$prefix/$installed" || { echo "FAIL: $installed not installed"; exit 1; }
done
cmake -S "$source/tests/install/external" -B "$scratch/external" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$scratch/external" -j2 >/dev/null
config=$source/configs/ch7_identification.yaml
"$scratch/external/run_in_memory" "$config" "$scratch/external.h5"
"$prefix/bin/tcpmsim" run "$config" -q -o "$scratch/program.h5"
differences=$(PYTHONPATH="$source/tests/python" "$python" -c "
import sys, record_compare
print(' '.join(record_compare.differences(sys.argv[1], sys.argv[2], ignore=['/@command_line'])))" \
  "$scratch/program.h5" "$scratch/external.h5")
[[ -z $differences ]] || { echo "FAIL: the records differ in: $differences"; exit 1; }
echo "ok: an external project built against $prefix writes the program's record"
# Its own controller kind (relay_controller.h), registered by name and used from YAML: a relay
# on the self-sensed force. It commands only the limits, keeps the estimate near the reference
# within its band (plus the thermal lag's overshoot), and its band is a parameter --set reaches.
relay_config=$source/tests/install/external/relay_force.yaml
"$scratch/external/run_with_relay" "$relay_config" "$scratch/relay.h5" >/dev/null
"$scratch/external/run_with_relay" "$relay_config" "$scratch/relay_wide.h5" "controller.band=20 mN" >/dev/null
"$python" -c "
import sys, h5py, numpy as np
switches = []
for path, band in ((sys.argv[1], 0.010), (sys.argv[2], 0.020)):
    with h5py.File(path) as record:
        t, power = record['time'][:], record['controller/power_command'][:]
        estimate, reference = record['estimator/force'][:], record['controller/reference'][:]
    assert set(np.unique(power)) == {0.10, 3.12}, np.unique(power)
    after = t >= 40.0
    worst = np.max(np.abs(estimate[after] - reference[after]))
    assert worst < 1.5 * band, (path, worst)
    switches.append(int(np.sum(np.diff(power) != 0)))
assert switches[1] < switches[0], switches
print('ok: a controller kind of the external project runs from YAML:', switches, 'switches')
" "$scratch/relay.h5" "$scratch/relay_wide.h5"
if message=$("$scratch/external/run_with_relay" "$relay_config" "$scratch/bad.h5" controller.gain=3 2>&1); then
  echo "FAIL: an unknown key of the user's kind was accepted"; exit 1
fi
[[ $message == *"controller.gain: unknown key 'gain'; known keys here: band, estimator, power_limits, reference, type"* ]] ||
  { echo "FAIL: the user's kind's bad key gave: $message"; exit 1; }
package=$(find "$prefix" -path '*/tcpmsim/__init__.py')
(cd "$scratch" && PYTHONPATH=$(dirname "$(dirname "$package")") "$python" -c "
import tcpmsim
assert tcpmsim.__file__.startswith('$prefix'), 'not the installed module: ' + tcpmsim.__file__
print('ok: installed tcpmsim', tcpmsim.__version__, 'from', tcpmsim.__file__)")
# The installed tcpmsim-plot finds its package where cmake --install put it (issue 30: the
# launcher looked beside itself and found nothing), run from outside the sources.
(cd "$scratch" && env -u PYTHONPATH "$prefix/bin/tcpmsim-plot" traces program.h5 -o installed_plot.png >/dev/null)
test -s "$scratch/installed_plot.png" || { echo "FAIL: the installed tcpmsim-plot drew nothing"; exit 1; }
echo "ok: the installed tcpmsim-plot draws from $prefix"
# The installed program packs the installed FMU library (<prefix>/lib/tcpmsim/tcpmsim_fmu.so),
# found beside it, not the build tree's.
fmu_library=$prefix/${TCPMSIM_LIBDIR:-lib}/tcpmsim/tcpmsim_fmu.so
test -s "$fmu_library" || { echo "FAIL: $fmu_library not installed"; exit 1; }
listing=$("$prefix/bin/tcpmsim" export-fmu "$source/configs/ch7_control/external_force.yaml" \
  -o "$scratch/muscle.fmu")
[[ $listing == *"library $fmu_library"* ]] ||
  { echo "FAIL: the installed export-fmu did not pack $fmu_library: $listing"; exit 1; }
(cd "$scratch" && mkdir unpacked && cd unpacked && "$python" -c "
import zipfile, sys; zipfile.ZipFile(sys.argv[1]).extractall()" "$scratch/muscle.fmu")
cmp "$fmu_library" "$scratch/unpacked/binaries/linux64/ch7_external_force.so" ||
  { echo "FAIL: the installed program did not pack the installed FMU library"; exit 1; }
echo "ok: the installed export-fmu packs $fmu_library"
