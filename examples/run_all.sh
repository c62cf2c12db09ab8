#!/usr/bin/env bash
# Runs every example from the source tree's root, as CI does; each checks what it shows.
# PYTHON selects the interpreter (default /usr/bin/python3, Debian's, that the module is built
# for); the module is found where scripts/quickstart.sh installed it, or through PYTHONPATH.
set -euo pipefail
cd "$(dirname "$0")/.."
python="${PYTHON:-/usr/bin/python3}"
for example in examples/*.py; do
  echo "== $example"
  "$python" "$example"
done
echo "examples: all $(ls examples/*.py | wc -l) ran"
