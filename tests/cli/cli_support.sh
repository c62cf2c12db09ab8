# Sourced by the command-line tests (test_cli.sh, test_cli_whole_runs.sh): a scratch directory
# removed on exit, a failure count, and the checks they are written in. Expects tcpmsim and
# source_dir to be set.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

expect() {  # expect CODE DESCRIPTION -- COMMAND...
  local code=$1 description=$2
  shift 3
  "$@" >"$work/out" 2>"$work/err"
  local actual=$?
  if [[ $actual != "$code" ]]; then
    echo "FAIL: $description: exit $actual, expected $code"; cat "$work/out" "$work/err"; failures=$((failures + 1))
  else
    echo "ok: $description (exit $code)"
  fi
}
contains() {  # contains FILE TEXT DESCRIPTION
  if grep -qF -- "$2" "$1"; then echo "ok: $3"; else echo "FAIL: $3: '$2' not in:"; cat "$1"; failures=$((failures + 1)); fi
}

# Provenance (issue 14): every HDF5 file under the scratch directory carries the version, git
# commit, command line and configs, and units on every numeric dataset.
check_provenance() {
  /usr/bin/python3 -c "import h5py" 2>/dev/null || return 0
  local written hdf5_files
  mapfile -t written < <(find "$work" -name '*.h5' -size +0 | sort)
  hdf5_files=$(/usr/bin/python3 -c 'import sys, h5py; print(sum(map(h5py.is_hdf5, sys.argv[1:])))' "${written[@]}")
  expect 0 "every file written carries its provenance and units" -- /usr/bin/python3 \
    "$source_dir/tests/python/check_provenance.py" "${written[@]}"
  contains "$work/out" "checked $hdf5_files file(s): 0 problem(s)" "the provenance check saw every file"
}
