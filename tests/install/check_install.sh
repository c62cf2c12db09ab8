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
package=$(find "$prefix" -name __init__.py -path '*tcpmsim*')
(cd "$scratch" && PYTHONPATH=$(dirname "$(dirname "$package")") "$python" -c "
import tcpmsim
print('ok: installed tcpmsim', tcpmsim.__version__, 'from', tcpmsim.__file__)")
