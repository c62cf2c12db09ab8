#!/usr/bin/env bash
# The layers, checked on every include: the engine (sim/) names no model; signals/ and models/
# build on the engine only (models/ never on controllers/); controllers/ on models/ and the
# engine; kinds/ (the standard registry) sees those; analysis/, sweep/ and identification/
# (fits and discovery) build on all of them in that order; fmu/ (FMI export) on the engine and
# the kinds; python/ (the module) on those below it; cli/,
# tests/ and bench/ see it all.
# Usage: check_layers.sh SOURCE_DIR
set -uo pipefail
cd "$1"
failures=0
check() {  # check LAYER ALLOWED-PREFIX-REGEX [EXCLUDED-DIRECTORY]
  local layer=$1 allowed=$2 excluded=${3:-}
  local bad
  if [[ ! -d $layer ]]; then  # a renamed layer must not pass by having nothing to check
    echo "FAIL: no layer directory $layer"
    failures=$((failures + 1))
    return
  fi
  bad=$(grep -rn --include='*.h' --include='*.cpp' ${excluded:+--exclude-dir="$excluded"} '#include "' "$layer" |
    grep -vE "#include \"($allowed)/" || true)
  if [[ -n $bad ]]; then
    echo "FAIL: $layer includes outside its layer ($allowed):"
    echo "$bad"
    failures=$((failures + 1))
  else
    echo "ok: $layer includes only $allowed"
  fi
}
check sim 'sim|tcpmsim'
check signals 'sim|signals'
check models 'sim|models'
check controllers 'sim|models|controllers'
check kinds 'sim|signals|models|controllers|kinds'
check analysis 'sim|signals|models|controllers|kinds|analysis|tcpmsim'
check sweep 'sim|signals|models|controllers|kinds|analysis|sweep|tcpmsim'
check identification 'sim|signals|models|controllers|kinds|analysis|sweep|identification|tcpmsim'
# fmu/fmi2/ is the FMI standard's header set, which includes its own files by their bare names.
check fmu 'sim|signals|models|controllers|kinds|fmu|tcpmsim' fmi2
check python 'sim|signals|models|controllers|kinds|analysis|sweep|identification|python|tcpmsim'
exit $((failures > 0))
