#!/usr/bin/env bash
# The layers, checked on every include: the engine (sim/) names no model; signals/ and models/
# build on the engine only (models/ never on controllers/); controllers/ on models/ and the
# engine; kinds/ (the standard registry) sees those; analysis/, sweep/ and identification/
# (fits and discovery) build on all of them in that order; python/ (the module) on those; cli/,
# tests/ and bench/ see it all.
# Usage: check_layers.sh SOURCE_DIR
set -uo pipefail
cd "$1"
failures=0
check() {  # check LAYER ALLOWED-PREFIX-REGEX
  local layer=$1 allowed=$2
  local bad
  if [[ ! -d $layer ]]; then  # a renamed layer must not pass by having nothing to check
    echo "FAIL: no layer directory $layer"
    failures=$((failures + 1))
    return
  fi
  bad=$(grep -rn --include='*.h' --include='*.cpp' '#include "' "$layer" | grep -vE "#include \"($allowed)/" || true)
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
check python 'sim|signals|models|controllers|kinds|analysis|sweep|identification|python|tcpmsim'
exit $((failures > 0))
