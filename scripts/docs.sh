#!/usr/bin/env bash
# The documentation site (issue 30): the generated reference pages against the program, every
# code block the README and the pages show, every notebook, then the site itself (Sphinx, MyST,
# furo; warnings are errors) into <build>/docs-html/. Uses a Release tree's program, Python
# module and plots: run scripts/test.sh (or scripts/quickstart.sh) first.
#   TCPMSIM_BUILD_DIR   that tree (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
build=${TCPMSIM_BUILD_DIR:-build}
if [[ ! -x $build/tcpmsim || ! -d $build/python ]]; then
  echo "docs: $build has no program or Python module; build it first (scripts/test.sh)" >&2
  exit 2
fi
started=$SECONDS
/usr/bin/python3 docs/make_commands_page.py --program "$build/tcpmsim" --check
/usr/bin/python3 docs/check_code_blocks.py --build "$build"
echo "docs: code blocks ran in $((SECONDS - started)) s"
# The site is built from a copy of docs/ whose notebooks are the executed ones.
site=$build/docs-src
/usr/bin/python3 docs/run_notebooks.py --build "$build" --site "$site"
echo "docs: notebooks ran at $((SECONDS - started)) s"
/usr/bin/python3 -m sphinx -W --keep-going -q -b html "$site" "$build/docs-html"
echo "docs: the site is $build/docs-html/index.html ($((SECONDS - started)) s)"
