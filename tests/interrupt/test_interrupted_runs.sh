#!/usr/bin/env bash
# An interrupted run keeps its data (issue 13).
#  - SIGTERM and SIGINT: the run stops after its current step and closes its record as
#    <out stem>.interrupted.h5 (status "interrupted", time_reached, every series as long as
#    /time), exit 143 or 130; a complete record at <out> is left as it was.
#  - SIGKILL: the <out>.partial file opens with h5py and holds samples up to the last flush
#    (at most a few seconds back); `tcpmsim recover` turns it into an .interrupted.h5 file.
# Usage: test_interrupted_runs.sh TCPMSIM_BINARY SOURCE_DIR
set -uo pipefail
tcpmsim=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python=/usr/bin/python3
fail() { echo "FAIL: $*"; exit 1; }
# The chapter-4 spring driven at its first eigenfrequency: thousands of steps a second of
# simulated time, so it is integrating when the signal comes, with a small record.
scenario="$source_dir/configs/ch4/sa_harmonic_first.yaml"
long=(--set 'scenario.duration=1000 s' --set 'output.rate=10 Hz' --set 'output.start=0 s' -q)

# Waits until the run's partial file holds samples (the first flush), at most 60 s, while the
# run ($2) lives.
wait_for_samples() {
  for _ in $(seq 1 600); do
    kill -0 "$2" 2>/dev/null || return 1
    # The writer holds HDF5's file lock: this poll reads past it, and retries what it misreads.
    [[ -s $1 ]] && HDF5_USE_FILE_LOCKING=FALSE $python - "$1" 2>/dev/null <<'PY' && return 0
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    sys.exit(0 if f["time"].shape[0] > 0 else 1)
PY
    sleep 0.1
  done
  return 1
}

# Checks a closed record: status, time_reached (when interrupted), every series as long as
# /time, the times increasing and none after time_reached.
check_record() {
  $python - "$@" <<'PY'
import sys, h5py, numpy as np
path, status = sys.argv[1], sys.argv[2]
with h5py.File(path, "r") as f:
    assert f.attrs["status"] == status, (f.attrs["status"], status)
    time = f["time"][:]
    assert time.size > 0, "no samples"
    assert np.all(np.diff(time) > 0), "times not increasing"
    if status == "interrupted":
        reached = float(f.attrs["time_reached"])
        assert time[-1] <= reached + 1e-9, (time[-1], reached)
        assert int(f.attrs["samples"]) == time.size, (int(f.attrs["samples"]), time.size)
    lengths = []
    f.visititems(lambda name, node: lengths.append((name, node.shape[0]))
                 if isinstance(node, h5py.Dataset) and node.maxshape[0] is None else None)
    short = [(n, k) for n, k in lengths if k != time.size]
    assert not short, short
    print(f"{path}: {status}, {time.size} samples up to t = {time[-1]:.0f} s, {len(lengths)} series")
PY
}

# A complete record at the output path, which no interrupted run may replace.
"$tcpmsim" run "$scenario" -q -o "$work/run.h5" || fail "the complete run"
before=$(sha256sum <"$work/run.h5")

for signal in TERM INT; do
  rm -f "$work/run.interrupted.h5"
  "$tcpmsim" run "$scenario" "${long[@]}" -o "$work/run.h5" 2>"$work/err" &
  pid=$!
  wait_for_samples "$work/run.h5.partial" $pid ||
    { kill -KILL $pid; fail "no samples reached the partial file: $(cat "$work/err")"; }
  kill -$signal $pid
  wait $pid
  code=$?
  expected=$([[ $signal == TERM ]] && echo 143 || echo 130)
  ((code == expected)) || fail "SIG$signal: exit $code, expected $expected: $(cat "$work/err")"
  grep -q "interrupted by SIG$signal" "$work/err" || fail "SIG$signal: no message: $(cat "$work/err")"
  [[ -e $work/run.h5.partial ]] && fail "SIG$signal: the partial file was left"
  check_record "$work/run.interrupted.h5" interrupted || fail "SIG$signal: the interrupted record"
  [[ $(sha256sum <"$work/run.h5") == "$before" ]] || fail "SIG$signal: the complete record was replaced"
  echo "ok: SIG$signal -> exit $code, $work/run.interrupted.h5 closed, the complete record kept"
done

rm -f "$work/run.interrupted.h5"
"$tcpmsim" run "$scenario" "${long[@]}" -o "$work/run.h5" &
pid=$!
wait_for_samples "$work/run.h5.partial" $pid ||
  { kill -KILL $pid; fail "no samples reached the partial file"; }
sleep 3  # several flushes on
kill -KILL $pid
wait $pid 2>/dev/null
$python - "$work/run.h5.partial" <<'PY' || fail "h5py cannot read the killed run's partial file"
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    time = f["time"][:]
    assert time.size > 0 and "status" not in f.attrs
    print(f"ok: SIGKILL: the partial file opens with h5py, {time.size} samples up to t = {time[-1]:.0f} s")
PY
"$tcpmsim" recover "$work/run.h5.partial" || fail "recover"
[[ -e $work/run.h5.partial ]] && fail "recover left the partial file"
check_record "$work/run.interrupted.h5" interrupted || fail "the recovered record"
"$tcpmsim" recover "$work/run.interrupted.h5" -o "$work/again.h5" 2>"$work/err"
code=$?
((code == 3)) || fail "recover of a closed record: exit $code, expected 3"
[[ $(sha256sum <"$work/run.h5") == "$before" ]] || fail "the complete record was replaced"
echo "ok: SIGKILL -> recover wrote $work/run.interrupted.h5; a closed record is refused: $(cat "$work/err")"

# A partial file killed before its first write is empty: recover says so, and for a sweep (whose
# runs are in <out>.parts) how to finish it instead.
: >"$work/empty.h5.partial"
"$tcpmsim" recover "$work/empty.h5.partial" 2>"$work/err"
code=$?
((code == 3)) || fail "recover of an empty file: exit $code, expected 3"
grep -q "it is empty: the run was stopped before it wrote anything" "$work/err" || fail "$(cat "$work/err")"
mkdir -p "$work/sweep.h5.parts" && : >"$work/sweep.h5.partial"
"$tcpmsim" recover "$work/sweep.h5.partial" 2>"$work/err"
grep -q "a sweep writes its file when it ends" "$work/err" || fail "$(cat "$work/err")"
echo "ok: an empty partial file is refused with its reason"
