#!/usr/bin/env bash
# The wheel (issue 30): `python3 -m build --no-isolation --wheel` from a copy of the sources,
# packing the compiled parts of BUILD_DIR (TCPMSIM_CMAKE_BUILD_DIR, so nothing is compiled
# twice), installed into a fresh virtual environment (--system-site-packages: Debian's numpy,
# h5py, matplotlib); then, from a directory outside the sources, the README's Python example,
# the program, tcpmsim-plot and export-fmu, each from the environment alone.
# Usage: check_wheel.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$(realpath "$1") source=$(realpath "$2") python=$3
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/source"
(cd "$source" && git ls-files -z 2>/dev/null | xargs -0 cp --parents -t "$scratch/source") ||
  (cd "$source" && tar --exclude='./build*' --exclude=./results -cf - . | tar -xf - -C "$scratch/source")
TCPMSIM_CMAKE_BUILD_DIR=$build "$python" -m build --no-isolation --wheel --outdir "$scratch/dist" \
  "$scratch/source" >"$scratch/build.log" 2>&1 || { cat "$scratch/build.log"; exit 1; }
wheel=$(ls "$scratch"/dist/tcpmsim-*.whl)
echo "ok: built $(basename "$wheel")"
"$python" -m venv --system-site-packages "$scratch/venv"
"$scratch/venv/bin/pip" install -q --no-index --no-deps "$wheel"
cd "$scratch"  # not the sources: everything below comes from the environment
"$scratch/venv/bin/python" -c "
import tcpmsim, sys
assert tcpmsim.__file__.startswith(sys.prefix), tcpmsim.__file__
r = tcpmsim.Scenario.from_yaml('$source/configs/ch7_identification.yaml').run()
print('ok: the README example from the environment: peak force', r['muscle/force'].max())"
"$scratch/venv/bin/tcpmsim" run "$source/configs/ch7_identification.yaml" -q -o run.h5
"$scratch/venv/bin/tcpmsim-plot" traces run.h5 -o run.png >/dev/null
test -s run.png || { echo "FAIL: tcpmsim-plot drew nothing"; exit 1; }
echo "ok: the environment's tcpmsim and tcpmsim-plot ran and drew run.png"
listing=$("$scratch/venv/bin/tcpmsim" export-fmu "$source/configs/ch7_control/external_force.yaml" -o m.fmu)
[[ $listing == *"library $scratch/venv/lib/"*"/tcpmsim/lib/tcpmsim/tcpmsim_fmu.so"* ]] ||
  { echo "FAIL: export-fmu did not pack the wheel's FMU library: $listing"; exit 1; }
echo "ok: the environment's export-fmu packs the wheel's FMU library"
