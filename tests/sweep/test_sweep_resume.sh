#!/usr/bin/env bash
# A sweep killed with SIGKILL midway and resumed gives the same file as one never interrupted
# (issue 11). Also: without --resume an interrupted sweep is not overwritten, no output file
# exists until the sweep is complete, a --resume beside a sweep that still runs is refused, and
# under a launcher the ranks' file equals one process'.
# Usage: test_sweep_resume.sh TCPMSIM_BINARY SOURCE_DIR [LAUNCHER...]
#   LAUNCHER: e.g. "mpirun -n 2" (then the sweep runs under it instead of on two threads)
set -uo pipefail
tcpmsim=$1
source_dir=$2
shift 2
launcher=("$@")
jobs=(--jobs 2)
((${#launcher[@]} > 0)) && jobs=()
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sweep="$source_dir/tests/sweep/resume_sweep.yaml"
python=/usr/bin/python3
fail() { echo "FAIL: $*"; exit 1; }
# The live processes of session `$1` (from /proc: a stat line's fields after the command are
# state, parent, group and session). A zombie is dead already, waiting for its parent to reap it:
# no signal removes it, so it is not counted.
session_members() {
  local stat line fields
  for stat in /proc/[0-9]*/stat; do
    read -r line 2>/dev/null <"$stat" || continue
    read -ra fields <<<"${line##*) }"
    [[ ${fields[3]} == "$1" && ${fields[0]} != Z ]] && echo "${stat//[^0-9]/}"
  done
}
# Kills every process of session `$1` and waits until none is left. A launcher's ranks are not
# in its process group (Open MPI gives each its own), only in its session: killing the group
# left them storing runs into the resumed sweep's parts.
kill_session() {
  local members
  for _ in $(seq 1 500); do
    members=$(session_members "$1")
    [[ -z $members ]] && return 0
    kill -KILL $members 2>/dev/null
    sleep 0.01
  done
  fail "processes of the killed sweep survive: $(session_members "$1")"
}

# Waits until the parts directory `$1` holds `$2` runs (at most 30 s).
wait_for_parts() {
  local count
  for _ in $(seq 1 3000); do
    count=$(find "$1" -name 'run_*.h5' 2>/dev/null | wc -l)
    ((count >= $2)) && return 0
    sleep 0.01
  done
}

"${launcher[@]}" "$tcpmsim" sweep "$sweep" "${jobs[@]}" -q -o "$work/whole.h5" || fail "the uninterrupted sweep"

setsid "${launcher[@]}" "$tcpmsim" sweep "$sweep" "${jobs[@]}" -q -o "$work/killed.h5" &
pid=$!
wait_for_parts "$work/killed.h5.parts" 4
kill_session "$pid"
{ wait "$pid"; } 2>/dev/null
[[ -e $work/killed.h5 ]] && fail "the sweep finished before it was killed (make it longer)"
done_runs=$(find "$work/killed.h5.parts" -name 'run_*.h5' | wc -l)
echo "ok: killed with $done_runs of 24 runs stored, no output file"

"$tcpmsim" sweep "$sweep" -q -o "$work/killed.h5" 2>"$work/err" && fail "a second start without --resume overwrote the parts"
grep -q -- "--resume" "$work/err" || fail "the refusal does not mention --resume: $(cat "$work/err")"
echo "ok: without --resume the interrupted sweep is refused"

"${launcher[@]}" "$tcpmsim" sweep "$sweep" "${jobs[@]}" --resume -o "$work/killed.h5" >"$work/out" 2>"$work/err" ||
  fail "the resume: $(cat "$work/out" "$work/err")"
grep -q "($done_runs done before the resume)" "$work/out" ||
  fail "the resume did not reuse exactly the $done_runs stored runs: $(cat "$work/out")"
[[ -e $work/killed.h5.parts ]] && fail "the parts were not removed after the merge"
$python "$source_dir/tools/compare_sweeps.py" "$work/whole.h5" "$work/killed.h5" || fail "the resumed sweep differs"
echo "ok: the resumed sweep equals the uninterrupted one"

# A sweep that still runs keeps every other out of its parts: a --resume beside it (which would
# redo its runs and collide with its writes) is refused, and it ends as if alone.
"${launcher[@]}" "$tcpmsim" sweep "$sweep" "${jobs[@]}" -q -o "$work/live.h5" &
pid=$!
wait_for_parts "$work/live.h5.parts" 2
"$tcpmsim" sweep "$sweep" --resume -q -o "$work/live.h5" 2>"$work/err" &&
  fail "a --resume beside a running sweep ran$([[ -e $work/live.h5 ]] && echo ': the first had ended (make it longer)')"
grep -qF "another sweep is writing into $work/live.h5.parts now" "$work/err" ||
  fail "the refusal beside a running sweep: $(cat "$work/err")"
wait "$pid" || fail "the running sweep failed beside the refused one"
$python "$source_dir/tools/compare_sweeps.py" "$work/whole.h5" "$work/live.h5" || fail "the running sweep differs"
echo "ok: a --resume beside a running sweep is refused, and the sweep ends as if alone"

if ((${#launcher[@]} > 0)); then  # and the ranks' file equals one process' on threads
  "$tcpmsim" sweep "$sweep" --jobs 2 -q -o "$work/threads.h5" || fail "the sweep on threads"
  $python "$source_dir/tools/compare_sweeps.py" "$work/whole.h5" "$work/threads.h5" || fail "ranks and threads differ"
  echo "ok: the sweep under ${launcher[*]} equals the one on two threads"
fi
