#!/usr/bin/env bash
# The command line: exit codes, located messages, and never a partial file that looks complete.
# Usage: test_cli.sh TCPMSIM_BINARY SOURCE_DIR
set -uo pipefail
tcpmsim=$1
source_dir=$2
source "$(dirname "$0")/cli_support.sh"

config="$source_dir/configs/ch7_identification.yaml"

expect 0 "--version" -- "$tcpmsim" --version
contains "$work/out" "tcpmsim 0.1.0" "version names the program"
# The commit a record names is the one the program was built from (a build after a commit
# configures again): never the commit of an earlier configuration.
if commit=$(git -C "$source_dir" rev-parse --short=12 HEAD 2>/dev/null); then
  contains "$work/out" "($commit)" "version names the commit the program was built from"
fi
expect 0 "--help" -- "$tcpmsim" --help
contains "$work/out" "run" "help lists the run command"
expect 2 "no command is a usage error" -- "$tcpmsim"
expect 2 "a missing scenario file is a usage error" -- "$tcpmsim" run "$work/none.yaml"
expect 0 "validate a good scenario" -- "$tcpmsim" validate "$config"
contains "$work/out" "output /muscle/force [N]" "validate lists the outputs"

sed "s/^    k1: .*/    k1: 10.8e-3 N/" "$config" >"$work/bad.yaml"
expect 3 "a wrong unit is a configuration error" -- "$tcpmsim" validate "$work/bad.yaml"
contains "$work/err" "bad.yaml:" "the error names the file"
contains "$work/err" "error: muscle.mechanics.k1: wrong unit in '10.8e-3 N': unit 'N' cannot be converted to 'N/m'" "the error names the key and the units"
expect 3 "a bad --set is a configuration error" -- "$tcpmsim" validate "$config" --set "solver.rtol=-1"
contains "$work/err" "command line (--set solver.rtol=-1): error: solver.rtol:" "the error points at the --set"

# Issue 30: a value of an implausible size warns at its key; --strict makes the warning an error.
sed "s/^    k1: .*/    k1: 14.04 N\/mm/" "$config" >"$work/slip.yaml"
expect 0 "a stiffness 1000 times too large is a warning" -- "$tcpmsim" validate "$work/slip.yaml"
contains "$work/err" "warning: muscle.mechanics.k1: '14.04 N/mm' is 14040 N/m, outside the typical range (0.1 to 5000 N/m)" "the warning names the key, the value and the typical range"
contains "$work/err" "1/1000 of it, 14.04 N/m, would be typical" "and the likely slip"
expect 3 "--strict makes it an error" -- "$tcpmsim" validate "$work/slip.yaml" --strict
contains "$work/err" "tcpmsim: --strict: 1 warning is an error" "--strict says why it stops"
expect 3 "run --strict stops before any work" -- "$tcpmsim" run "$work/slip.yaml" --strict -o "$work/slip.h5"
[[ ! -e $work/slip.h5 && ! -e $work/slip.h5.partial ]] && echo "ok: no record" || { echo "FAIL: run --strict wrote a record"; failures=$((failures + 1)); }

expect 0 "several scenarios run as a batch on threads" -- "$tcpmsim" run "$config" \
  "$source_dir/configs/composition/two_muscles.yaml" --jobs 2 --set "scenario.duration=5 s" \
  --output-dir "$work/batch" --quiet
[[ -s $work/batch/ch7_identification.h5 && -s $work/batch/two_muscles.h5 ]] && echo "ok: each record under its scenario's name" || { echo "FAIL: batch records missing"; failures=$((failures + 1)); }
expect 2 "-o with several scenarios is a usage error" -- "$tcpmsim" run "$config" "$source_dir/configs/composition/two_muscles.yaml" -o "$work/x.h5"
expect 0 "kinds lists every kind" -- "$tcpmsim" kinds
contains "$work/out" "maxwell_branch" "kinds names the effects"
contains "$work/out" "stiffness                           quantity in N/m, a positive value; required" "kinds gives a key's unit, range and whether it is required"
pair="$source_dir/configs/composition/two_muscles.yaml"
expect 0 "validate a scenario with named instances" -- "$tcpmsim" validate "$pair"
contains "$work/out" "output /m2/force [N]" "outputs are recorded under the instance's name"
contains "$work/out" "parameter m2.mechanics.k2 = 5.4 N/m" "validate lists the parameters by path, in SI"
expect 3 "a bad value for an instance's parameter is a configuration error" -- "$tcpmsim" validate "$pair" \
  --set "m2.mechanics.k2=-3 mN/mm"
contains "$work/err" "command line (--set m2.mechanics.k2=-3 mN/mm): error: muscles.m2.mechanics.k2: expected a non-negative value in N/m, got '-3 mN/mm'" "the error names the --set and the key"
expect 0 "an instance's parameter is set by its path, with units" -- "$tcpmsim" validate "$pair" \
  --set "m2.mechanics.k2=3 mN/mm"
contains "$work/out" "parameter m2.mechanics.k2 = 3 N/m" "validate lists the value the run takes"
contains "$work/out" "parameter m1.mechanics.k2 = 2.7 N/m" "and only that instance's parameter changes"
expect 0 "a run takes it" -- "$tcpmsim" run "$pair" \
  --set "m2.mechanics.k2=3 mN/mm" --set "scenario.duration=10 s" -o "$work/pair.h5" --quiet
expect 3 "a key of a section is not an instance's name" -- "$tcpmsim" validate "$config" \
  --set "duration=1 s"
contains "$work/err" "error: duration: unknown key 'duration'" "only plural sections' names expand"

# Issue 13: one located message for each class of bad input.
: >"$work/empty.yaml"
expect 3 "an empty scenario file is a configuration error" -- "$tcpmsim" validate "$work/empty.yaml"
contains "$work/err" "empty.yaml:1:1: error: the file is empty (or holds only comments); expected a mapping with 'scenario'" "the empty file is named as such, at its start"
printf 'scenario: {name: x}  # a\0b\n' >"$work/nul.yaml"
expect 3 "a NUL byte is a configuration error" -- "$tcpmsim" validate "$work/nul.yaml"
contains "$work/err" "nul.yaml:1:25: error: the file holds a NUL byte (binary or corrupted?)" "the NUL byte is located"
printf 'scenario: {name: "x\033[2J\001}\n' >"$work/control.yaml"
expect 3 "a control character is a configuration error" -- "$tcpmsim" validate "$work/control.yaml"
LC_ALL=C grep -q '[[:cntrl:]]' "$work/err" && { echo "FAIL: a raw control byte in the message"; cat -v "$work/err"; failures=$((failures + 1)); } || echo "ok: no raw control byte in the message"
contains "$work/err" 'control.yaml:1:20: error: the file holds the control character \x1b' "the control character is escaped"
expect 3 "a --set that adds a section the scenario does not have" -- "$tcpmsim" validate "$config" --set foo.bar=1
contains "$work/err" "command line (--set foo.bar=1): error: foo: unknown key 'foo'" "the error names the --set, not the file"
expect 3 "a --set of a key another load type takes" -- "$tcpmsim" validate "$config" --set "load.mass=1 kg"
contains "$work/err" "command line (--set load.mass=1 kg): error: load.mass: 'mass' is not used with type: deflection; it belongs to type: hanging_mass" "the error names the types that take the key"
sed "s/^    k1: .*/    k1: 10.8e-3/" "$config" >"$work/bare.yaml"
expect 3 "a bare number for a stiffness is a configuration error" -- "$tcpmsim" validate "$work/bare.yaml"
contains "$work/err" "error: muscle.mechanics.k1: '10.8e-3' has no unit; expected a stiffness (force/length), e.g. N/m or N/mm" "the hint names the dimension, not the number in SI"
sed "s/^    lambda_x: \(.*\)/    lambda_x: [\1/" "$config" >"$work/unclosed.yaml"
expect 3 "an unclosed bracket is a configuration error" -- "$tcpmsim" validate "$work/unclosed.yaml"
line=$(grep -n "lambda_x: \[" "$work/unclosed.yaml" | cut -d: -f1)
contains "$work/err" "unclosed.yaml:$line:15: error: invalid YAML: unclosed flow sequence '[' opened here" "the error is where the bracket opens"

expect 0 "run a short scenario" -- "$tcpmsim" run "$config" --set "scenario.duration=5 s" -o "$work/run.h5" --quiet
[[ -s $work/run.h5 && ! -e $work/run.h5.partial ]] && echo "ok: complete record, no partial" || { echo "FAIL: record"; failures=$((failures + 1)); }

expect 1 "a solver failure exits 1" -- "$tcpmsim" run "$config" --set "solver.max_steps=3" -o "$work/fail.h5"
contains "$work/err" "more than 3 solver steps" "the failure is explained"
[[ -s $work/fail.failed.h5 && ! -e $work/fail.h5 && ! -e $work/fail.h5.partial ]] \
  && echo "ok: failed record kept as .failed.h5 only" || { echo "FAIL: failed record"; ls "$work"; failures=$((failures + 1)); }

# An output that is the command's own input would replace it; one ending in '/' names a directory.
cp "$config" "$work/own.yaml"
expect 2 "run -o its own scenario is a usage error" -- "$tcpmsim" run "$work/own.yaml" --set "scenario.duration=1 s" -o "$work/own.yaml"
contains "$work/err" "-o $work/own.yaml is $work/own.yaml, an input of this command: writing would replace it" "the output is named as the input"
cmp -s "$config" "$work/own.yaml" && echo "ok: the scenario is untouched" || { echo "FAIL: run replaced its scenario"; failures=$((failures + 1)); }
expect 4 "run -o a path ending in / is an output error before the run" -- "$tcpmsim" run "$config" --set "scenario.duration=1 s" -o "$work/newdir/"
contains "$work/err" "cannot write $work/newdir/: it names a directory (it ends in /)" "the output error says why"
[[ ! -e $work/newdir ]] && echo "ok: nothing made for an output ending in /" || { echo "FAIL: $work/newdir made"; failures=$((failures + 1)); }
expect 4 "an unwritable output is an output error" -- "$tcpmsim" run "$config" --set "scenario.duration=1 s" -o /proc/tcpmsim/run.h5

# The analysis commands share the scenario rules: usage errors exit 2, configuration errors 3.
tasks="$source_dir/configs/ch7_control"
expect 2 "control-tasks without a scenario is a usage error" -- "$tcpmsim" control-tasks
expect 3 "a bad --set on control-tasks is a configuration error" -- "$tcpmsim" control-tasks \
  "$tasks/force_steps.yaml" --set "controller.gains.proportional=540 W" -o "$work/tasks.h5"
contains "$work/err" "error: controller.gains.proportional:" "control-tasks names the key"
expect 3 "a one-step sequence is a configuration error, not an exception" -- "$tcpmsim" control-tasks \
  "$tasks/force_steps.yaml" --set "controller.reference.steps=1" -o "$work/tasks.h5"
contains "$work/err" "error: controller.reference.steps:" "the step count's key is named"
[[ ! -e $work/tasks.h5 ]] && echo "ok: no control-task file after the error" || { echo "FAIL: tasks.h5 written"; failures=$((failures + 1)); }
expect 0 "control-tasks writes its report" -- "$tcpmsim" control-tasks "$tasks/force_steps.yaml" \
  --no-calibration --set "scenario.duration=60 s" -o "$work/tasks.h5"
contains "$work/out" "thesis 2.1-5.1 s" "control-tasks prints the thesis' values beside ours"
[[ -s $work/tasks.h5 ]] && echo "ok: control-task file written" || { echo "FAIL: no tasks.h5"; failures=$((failures + 1)); }
mkdir "$work/taken.h5"
expect 4 "a control-task output the file system refuses is an output error" -- "$tcpmsim" control-tasks \
  "$tasks/force_steps.yaml" --no-calibration --set "scenario.duration=60 s" -o "$work/taken.h5"
contains "$work/err" "cannot write $work/taken.h5" "the output error names the file"
expect 4 "two results under one name are an output error, not a crash" -- "$tcpmsim" control-tasks \
  "$tasks/force_steps.yaml" "$tasks/force_steps.yaml" --no-calibration --set "scenario.duration=60 s" \
  -o "$work/twice.h5"
[[ ! -e $work/twice.h5 && ! -e $work/twice.h5.partial ]] && echo "ok: no file after the output error" \
  || { echo "FAIL: twice.h5 left behind"; ls "$work"; failures=$((failures + 1)); }
expect 4 "a spring-force output the file system refuses is an output error" -- "$tcpmsim" spring-forces \
  "$source_dir/configs/ch4/st_heel_strike.yaml" -o "$work/taken.h5" --quiet
expect 2 "an analysis window longer than the record is a usage error, not analysed short" -- "$tcpmsim" \
  spring-forces "$source_dir/configs/ch4/st_heel_strike.yaml" --window 1 -o "$work/window.h5"
contains "$work/err" "--window: $source_dir/configs/ch4/st_heel_strike.yaml: the analysis window (1 s) must lie within the recorded" "the window error names the option and says why"
# A coil spring the scenario names otherwise than 'spring': refused before any run (it was an
# output error, exit 4, from the run's thread).
sed 's/^spring:$/springs:\n  left:/; /^springs:/,/^[a-z]/{/^ /s/^/  /}' \
  "$source_dir/configs/ch4/st_heel_strike.yaml" >"$work/named_spring.yaml"
expect 0 "a coil spring named 'left' is a valid scenario" -- "$tcpmsim" validate "$work/named_spring.yaml"
expect 2 "spring-forces on a spring named otherwise is a usage error" -- "$tcpmsim" spring-forces \
  "$work/named_spring.yaml" -o "$work/named.h5"
contains "$work/err" "spring-forces reads the outputs of a coil spring named 'spring' (spring.input_force); $work/named_spring.yaml names its spring otherwise" "the error says which name it reads"
expect 2 "spring-forces with a missing file is a usage error" -- "$tcpmsim" spring-forces "$work/none.yaml"
# An analysis given a scenario of another kind is a usage error that names the file and what the
# command takes (issue 13: it was an internal error).
expect 2 "spring-forces on a muscle scenario is a usage error" -- "$tcpmsim" spring-forces "$config" -o "$work/sf.h5"
contains "$work/err" "spring-forces takes coil-spring scenarios with an inductance sensor (configs/ch4/*.yaml); $config is not one" "the wrong-kind error names the file and the kind"
[[ ! -e $work/sf.h5 ]] && echo "ok: nothing written for the wrong kind" || { echo "FAIL: output for the wrong kind"; failures=$((failures + 1)); }
expect 2 "coil-fit with a missing data directory is a usage error" -- "$tcpmsim" coil-fit \
  "$source_dir/configs/springs/s1.yaml" --data "$work/none"
# Issue 13: control-tasks on a coil spring blamed its own calibration --set; a usage error now.
expect 2 "control-tasks on a coil-spring scenario is a usage error" -- "$tcpmsim" control-tasks \
  "$source_dir/configs/ch4/sa_harmonic_first.yaml" -o "$work/ct.h5"
contains "$work/err" "control-tasks takes the chapter-7 self-sensing control scenarios (configs/ch7_control/*.yaml, configs/pair/*.yaml); $source_dir/configs/ch4/sa_harmonic_first.yaml is not one" "the wrong-kind error names the file and what the command takes"
[[ ! -e $work/ct.h5 ]] && echo "ok: nothing written for the wrong kind" || { echo "FAIL: control-tasks output for the wrong kind"; failures=$((failures + 1)); }
expect 3 "coil-fit on a muscle scenario is a configuration error" -- "$tcpmsim" coil-fit "$config" -o "$work/cf.h5"
contains "$work/err" "$config:" "the coil-fit error names the file"
contains "$work/err" "missing required key 'coil_spring'" "the coil-fit error says what the file lacks"
# The spring file names its data beside it: coil-fit runs from any directory (issue 13).
expect 0 "coil-fit finds the thesis' data from another working directory" -- \
  bash -c 'cd "$1" && "$2" coil-fit "$3" -o "$1/coil_fit.h5" --quiet' _ "$work" "$tcpmsim" \
  "$source_dir/configs/springs/s1.yaml"
[[ -s $work/coil_fit.h5 ]] && echo "ok: coil-fit wrote its file" || { echo "FAIL: no coil_fit.h5"; failures=$((failures + 1)); }
# A geometry whose model inductance turns as the coil is stretched (Rosa* on a short S4, through
# its published Nagaoka defect) has no inverse: that model's deflection is NaN, and why is said;
# the other models are analysed (it was an internal error from the interpolation).
sed -e "s|^  data: .*|  data: $source_dir/data/coil-spring-inductance|" -e 's|^  body_length: .*|  body_length: 20 mm|' \
  "$source_dir/configs/springs/s4.yaml" >"$work/short_spring.yaml"
expect 0 "a spring outside one coil model's range is analysed with the others" -- "$tcpmsim" coil-fit \
  "$work/short_spring.yaml" -o "$work/short.h5"
contains "$work/out" "S4_01, Rosa* (nan): its inductance turns near 22.695 mm, between 17.8 and 27.59 mm: this geometry (8.09091 turns) lies outside the model" "the report says which model has no inverse and why"
expect 2 "an explicit --data stays relative to the working directory" -- \
  bash -c 'cd "$1" && "$2" coil-fit "$3" --data data/coil-spring-inductance -o "$1/none.h5"' _ \
  "$work" "$tcpmsim" "$source_dir/configs/springs/s1.yaml"

# fit: a measurement (the chapter-7 bench, simulated), a model replaying it, and its errors (the
# whole fits and discover: test_cli_whole_runs.sh).
discover="$source_dir/configs/discover"
expect 0 "the chapter-7 bench writes a measurement" -- "$tcpmsim" run "$discover/ch7_protocol.yaml" -o "$work/bench.h5" --quiet
printf 'time[s],power[W],deflection[mm],force[mN]\n0,1,20,107\n1,1,nan,107\n' >"$work/bad.csv"
expect 3 "a bad measurement is a data-file error" -- "$tcpmsim" fit "$discover/ch7_fit.yaml" --data "$work/bad.csv" --out "$work/fit"
contains "$work/err" "bad.csv:3:5: error: field 3 (deflection [mm]): expected a finite number, got 'nan'" "the data error is located"
[[ ! -e $work/fit ]] && echo "ok: nothing written on a data error" || { echo "FAIL: a fit directory after a data error"; failures=$((failures + 1)); }
# Issue 31: bytes of no UTF-8 sequence are quoted escaped, never echoed raw.
printf 'time[s],power[W],deflection[mm],force[mN]\n0,1,20,107\n1,1,20,\377\376\200\n' >"$work/garbage.csv"
expect 3 "binary garbage in a measurement is a data-file error" -- "$tcpmsim" fit "$discover/ch7_fit.yaml" --data "$work/garbage.csv" --out "$work/fit"
contains "$work/err" 'garbage.csv:3:8: error: field 4 (force [mN]):' "the garbage is located"
contains "$work/err" "'\xff\xfe\x80'" "the garbage is escaped"
iconv -f UTF-8 -t UTF-8 "$work/err" >/dev/null 2>&1 && echo "ok: the message is UTF-8" || { echo "FAIL: raw bytes in the message"; failures=$((failures + 1)); }
expect 3 "a model without its measurement is a configuration error" -- "$tcpmsim" run "$discover/ch7_base.yaml" -o "$work/none.h5"
contains "$work/err" "expected a file to replay: 'file', or the scenario's measurement.file" "the error says how to give the measurement"
expect 0 "the model runs alone with --set measurement.file" -- "$tcpmsim" run "$discover/ch7_base.yaml" --set "measurement.file=$work/bench.h5" -o "$work/base.h5" --quiet
expect 0 "measure reads the model with the bench's instruments" -- "$tcpmsim" measure "$discover/ch7_base.yaml" \
  --set "measurement.file=$work/bench.h5" --bench "$discover/ch7_bench.yaml" -o "$work/measured.csv" --quiet
head -1 "$work/measured.csv" >"$work/header"
contains "$work/header" "time[s],power[W],deflection[mm],force[mN],inductance_measure[1]" "the measurement's headings name channels and units"
# A fit that fails (a force of 1e305 N: its squared residuals overflow) says why, exits 1, and
# leaves no empty output directory that would look like a result.
awk -F, 'NR == 100 { $4 = "1e308" } 1' OFS=, "$work/measured.csv" >"$work/overflow.csv"
expect 1 "a fit the data make impossible fails with its reason" -- "$tcpmsim" fit "$discover/ch7_fit.yaml" \
  --data "$work/overflow.csv" --out "$work/fit_failed" --set 'multistart.starts=0'
contains "$work/err" "the squared residuals overflow" "the failed fit says why"
[[ ! -e $work/fit_failed ]] && echo "ok: a failed fit leaves no output directory" || { echo "FAIL: $work/fit_failed exists"; failures=$((failures + 1)); }
# An output directory that exists but cannot be written into (/proc, even for root) is refused
# before any fit: it failed only when the results were written, after the whole fit.
expect 4 "fit into a directory it cannot write is an output error before the fit" -- "$tcpmsim" fit \
  "$discover/ch7_fit.yaml" --data "$work/measured.csv" --out /proc
contains "$work/err" "tcpmsim: cannot write into /proc: " "the fit names the directory and the system's reason"
expect 4 "discover into a directory it cannot write is an output error before the base fit" -- \
  "$tcpmsim" discover --model "$discover/ch7_base.yaml" --data "$work/measured.csv" \
  --inputs power,deflection --outputs force --validate-from 400 --out /proc
contains "$work/err" "tcpmsim: cannot write into /proc: " "discover names the directory and the system's reason"
# Issue 31: a window that holds no sample (between two samples, or inside a gap in the data's
# times) is a located configuration error, not a crash, and nothing is written.
fit_file() {  # fit_file NAME IDENTIFICATION [VALIDATION]: a one-parameter fit of the base model
  printf 'model: %s\noutputs: [{channel: force, output: load.force, noise: 1 mN}]\nparameters: [{path: muscle.mechanics.k1, bounds: [5 N/m, 20 N/m]}]\nidentification: %s\n' \
    "$discover/ch7_base.yaml" "$2" >"$work/$1"
  [[ -n ${3:-} ]] && printf 'validation: %s\n' "$3" >>"$work/$1"
}
fit_file between.yaml '[100.01 s, 100.02 s]'
expect 3 "an identification window between two samples is a configuration error" -- "$tcpmsim" fit \
  "$work/between.yaml" --data "$work/measured.csv" --out "$work/fit_between"
contains "$work/err" "between.yaml:4:17: error: identification: the window [100.01 s, 100.02 s] holds no sample of the data" "the empty identification window is located"
fit_file empty_validation.yaml '[0 s, 400 s]' '[500.01 s, 500.02 s]'
expect 3 "a validation window without a sample is a configuration error" -- "$tcpmsim" fit \
  "$work/empty_validation.yaml" --data "$work/measured.csv" --out "$work/fit_between"
contains "$work/err" "empty_validation.yaml:5:13: error: validation: the window [500.01 s, 500.02 s] holds no sample of the data" "the empty validation window is located"
awk -F, 'NR == 1 || $1 < 100 || $1 > 300' "$work/measured.csv" >"$work/gap.csv"
fit_file in_gap.yaml '[0 s, 80 s]' '[150 s, 250 s]'
expect 3 "a window inside a gap in the data is a configuration error" -- "$tcpmsim" fit \
  "$work/in_gap.yaml" --data "$work/gap.csv" --out "$work/fit_between"
contains "$work/err" "in_gap.yaml:5:13: error: validation: the window [150 s, 250 s] holds no sample of the data" "the window inside the gap is located"
[[ ! -e $work/fit_between ]] && echo "ok: nothing written for an empty window" || { echo "FAIL: a fit directory after a window error"; failures=$((failures + 1)); }
# The same measured channel compared twice would write one dataset twice, after the whole fit.
fit_file twice.yaml '[0 s, 400 s]'
sed -i 's|^outputs: .*|outputs: [{channel: force, output: load.force, noise: 1 mN}, {channel: force, output: load.force, noise: 2 mN}]|' "$work/twice.yaml"
expect 3 "a fit comparing a channel twice is a configuration error" -- "$tcpmsim" fit "$work/twice.yaml" \
  --data "$work/measured.csv" --out "$work/fit_twice"
contains "$work/err" "twice.yaml:2:" "the second comparison is located"
contains "$work/err" "outputs[1].channel: channel 'force' is compared twice" "the channel compared twice is named"
[[ ! -e $work/fit_twice ]] && echo "ok: nothing written for a channel compared twice" || { echo "FAIL: a fit directory after the error"; failures=$((failures + 1)); }
# Issue 31: a window of fewer samples than parameters + 1 fits them exactly, with no residual left
# to estimate their errors: refused, not reported as identified.
fit_file one_sample.yaml '[100 s, 100.03 s]'
expect 3 "an identification window of one sample for one parameter is a configuration error" -- \
  "$tcpmsim" fit "$work/one_sample.yaml" --data "$work/measured.csv" --out "$work/fit_between"
contains "$work/err" "one_sample.yaml:4:17: error: identification: the window [100 s, 100.03 s] holds 1 sample of the data; a fit of 1 parameter needs at least 2" "the too-short window is located, with the count it needs"
[[ ! -e $work/fit_between ]] && echo "ok: nothing written for a window too short" || { echo "FAIL: a fit directory after a window error"; failures=$((failures + 1)); }
# Issue 31: the model file is located at the fit file's model key, whatever is wrong with it.
sed "s|^model: .*|model: nowhere.yaml|" "$work/one_sample.yaml" >"$work/no_model.yaml"
expect 3 "a fit whose model file is missing is a configuration error" -- "$tcpmsim" fit \
  "$work/no_model.yaml" --data "$work/measured.csv" --out "$work/fit_between"
contains "$work/err" "no_model.yaml:1:8: error: model: no scenario file '$work/nowhere.yaml'" "the missing model is located at its key"
sed "s|^model: .*|model: $source_dir/configs/sweeps/design_example.yaml|" "$work/one_sample.yaml" >"$work/sweep_model.yaml"
expect 3 "a sweep file as the model is a configuration error" -- "$tcpmsim" fit \
  "$work/sweep_model.yaml" --data "$work/measured.csv" --out "$work/fit_between"
contains "$work/err" "sweep_model.yaml:1:8: error: model: '$source_dir/configs/sweeps/design_example.yaml' is no scenario the fit can run" "the wrong model is blamed at its key, not on a --set never typed"
# Issue 31: a measured force so large that the squared residuals overflow: the fit fails with
# the sample and the values that did it, not an empty reason.
awk -F, -v OFS=, 'NR == 101 { $4 = "1e308" } { print }' "$work/measured.csv" >"$work/huge_force.csv"
fit_file huge_force.yaml '[0 s, 400 s]'
expect 1 "a fit whose residuals overflow fails with its reason" -- "$tcpmsim" fit \
  "$work/huge_force.yaml" --data "$work/huge_force.csv" --out "$work/fit_huge" --set multistart.starts=0
contains "$work/err" "the first failure: the residual of load.force against the measured force at t = 6.1875 s is 1e+308 noise widths: the squared residuals overflow (measured 1e+305 N, noise 0.001 N)" "the reason names the sample and the values"
# Issue 31: a sweep whose axes multiply beyond the cap is refused before a run is made.
printf 'sweep: {name: huge}\nscenario: %s\naxes:\n  - {parameter: muscle.thermal.conductance, range: {from: 1 W/K, to: 2 W/K, count: 1000}}\n  - {parameter: muscle.thermal.heat_capacity, range: {from: 1 J/K, to: 2 J/K, count: 1000}}\n  - {parameter: muscle.mechanics.k1, range: {from: 1 N/m, to: 2 N/m, count: 1000}}\n' \
  "$source_dir/configs/sweeps/thermal_step.yaml" >"$work/huge_sweep.yaml"
expect 3 "a sweep of 1e9 runs is a configuration error" -- "$tcpmsim" sweep "$work/huge_sweep.yaml" -o "$work/huge.h5"
contains "$work/err" "huge_sweep.yaml:3:1: error: axes: the axes make 1000 x 1000 x 1000 = 1e+09 runs, over the limit of 1e+06 runs a sweep" "the sweep's size is refused with the product and the cap"
[[ ! -e $work/huge.h5 && ! -e $work/huge.h5.partial ]] && echo "ok: no sweep file after the size error" || { echo "FAIL: a sweep file after the size error"; failures=$((failures + 1)); }
# Issue 31: an output path that cannot be a file is refused before any work, as run refuses it.
mkdir "$work/outdir"
expect 4 "measure -o a directory is an output error before the run" -- "$tcpmsim" measure "$discover/ch7_base.yaml" \
  --set "measurement.file=$work/bench.h5" --bench "$discover/ch7_bench.yaml" -o "$work/outdir"
contains "$work/err" "tcpmsim: cannot write $work/outdir: it is a directory" "measure names the output and why"
[[ ! -e $work/outdir.partial ]] && echo "ok: no partial measurement" || { echo "FAIL: measure left $work/outdir.partial"; failures=$((failures + 1)); }
expect 4 "sweep -o a directory is an output error before any run" -- "$tcpmsim" sweep \
  "$source_dir/configs/sweeps/thermal_hA_C.yaml" -o "$work/outdir" --quiet
contains "$work/err" "tcpmsim: cannot write $work/outdir: it is a directory" "sweep names the output and why"
[[ ! -e $work/outdir.parts ]] && echo "ok: no sweep run before the output error" || { echo "FAIL: the sweep ran before refusing its output"; failures=$((failures + 1)); }
# discover: a request it cannot serve is refused before any fit, and nothing is written.
expect 2 "discover with an input the model does not replay is a usage error" -- "$tcpmsim" discover \
  --model "$discover/ch7_base.yaml" --data "$work/measured.csv" --inputs power,force --outputs force \
  --validate-from 400 --out "$work/discover"
contains "$work/err" "tcpmsim: --inputs: the model" "the discover error names the option"
contains "$work/err" "replays no channel 'force'" "the discover error says what is missing"
expect 2 "discover with an unknown effect is a usage error" -- "$tcpmsim" discover \
  --model "$discover/ch7_base.yaml" --data "$work/measured.csv" --inputs power,deflection \
  --outputs force --validate-from 400 --effects warm_up --out "$work/discover"
contains "$work/err" "--effects: no effect 'warm_up'" "the unknown effect is named"
expect 3 "discover on a bad measurement is a data-file error" -- "$tcpmsim" discover \
  --model "$discover/ch7_base.yaml" --data "$work/bad.csv" --inputs power,deflection \
  --outputs force --validate-from 0.5 --out "$work/discover"
[[ ! -e $work/discover ]] && echo "ok: nothing written on a discover error" || { echo "FAIL: a discover directory after an error"; failures=$((failures + 1)); }
expect 2 "discover --noise names an output it compares" -- "$tcpmsim" discover \
  --model "$discover/ch7_base.yaml" --data "$work/measured.csv" --inputs power,deflection \
  --outputs force --validate-from 400 --noise torque=2mN --out "$work/discover"
contains "$work/err" "--noise torque=2mN: expected OUTPUT=VALUE UNIT for a compared output" "the --noise error says what it expects"
expect 2 "discover's default parameters need a value to scale their bounds from" -- "$tcpmsim" discover \
  --model "$discover/ch7_base.yaml" --data "$work/measured.csv" --inputs power,deflection \
  --outputs force --validate-from 400 --set muscle.mechanics.force_offset=0N --out "$work/discover"
contains "$work/err" "one of the parameters discover fits by default" "the message says the parameter was discover's choice"
contains "$work/err" "(--set muscle.mechanics.force_offset=VALUE UNIT) or name the parameters to fit (--parameters)" "and how to go on"
expect 2 "discover --alias-correlation is a correlation" -- "$tcpmsim" discover \
  --model "$discover/ch7_base.yaml" --data "$work/measured.csv" --inputs power,deflection \
  --outputs force --validate-from 400 --alias-correlation 1.5 --out "$work/discover"
contains "$work/err" "--alias-correlation: Value 1.5 not in range 0.000000 to 1.000000" "the range is stated"
expect 2 "discover --max-effects counts runs, from one" -- "$tcpmsim" discover \
  --model "$discover/ch7_base.yaml" --data "$work/measured.csv" --inputs power,deflection \
  --outputs force --validate-from 400 --max-effects 0 --out "$work/discover"
contains "$work/err" "--max-effects: Value 0 not in range 1 to 10" "the range is stated"

# analyze: any record's step metrics and frequency response; a request the record cannot serve
# is a usage error naming what it has.
expect 0 "a run of power steps" -- "$tcpmsim" run "$source_dir/configs/analysis/power_steps.yaml" \
  --set "scenario.duration=400 s" -o "$work/steps.h5" --quiet
expect 0 "analyze gives the step metrics of any channel" -- "$tcpmsim" analyze "$work/steps.h5" \
  --response muscle/force --reference drive/power -o "$work/analysis.h5"
contains "$work/out" "step response of muscle/force [N] against drive/power [W]" "analyze names the channels and units"
# Issue 30: analyses of other channels of one record go to files of their own by default.
mkdir -p "$work/analyses"
expect 0 "analyze a record's force steps" -- bash -c "cd '$work/analyses' && '$tcpmsim' analyze ../steps.h5 --response muscle/force --reference drive/power -q"
expect 0 "and its temperature steps" -- bash -c "cd '$work/analyses' && '$tcpmsim' analyze ../steps.h5 --response muscle/temperature --reference drive/power -q"
[[ -s $work/analyses/results/steps_muscle_force_steps.h5 && -s $work/analyses/results/steps_muscle_temperature_steps.h5 ]] && echo "ok: two analyses, two files" || { echo "FAIL: the default analysis files"; ls -R "$work/analyses"; failures=$((failures + 1)); }
expect 2 "analyze names a channel the record lacks" -- "$tcpmsim" analyze "$work/run.h5" \
  --response muscle/forse -o "$work/none_analysis.h5"
contains "$work/err" "has no channel 'muscle/forse'; it has" "the analysis error lists the channels"
[[ ! -e $work/none_analysis.h5 ]] && echo "ok: no analysis file after the error" || { echo "FAIL: an analysis file after an error"; failures=$((failures + 1)); }
expect 2 "analyze of a file that is no record is a usage error" -- "$tcpmsim" analyze "$work/analysis.h5" \
  --response muscle/force -o "$work/none_analysis.h5"
contains "$work/err" "is not a tcpmsim record" "the error says what the file is not"
# Issue 31: a damaged file, or an HDF5 file tcpmsim did not write, is a data-file error (exit 3)
# whose message says so in its own words.
head -c 2000 "$work/steps.h5" >"$work/damaged.h5"
expect 3 "analyze of a damaged file is a data-file error" -- "$tcpmsim" analyze "$work/damaged.h5" \
  --response muscle/force -o "$work/none_analysis.h5"
contains "$work/err" "$work/damaged.h5: error: cannot read it as HDF5: damaged, truncated, or not an HDF5 file" "the damaged file is named and why"
grep -q "H5File" "$work/err" && { echo "FAIL: HDF5's own words leak"; failures=$((failures + 1)); } || echo "ok: no HDF5 function name in the message"
rm -f "$work/damaged.h5"
# Issue 31: a window that holds too little is named by the options that gave it.
expect 2 "analyze of a window past the record's end is a usage error" -- "$tcpmsim" analyze "$work/steps.h5" \
  --response muscle/force --reference drive/power --from 700 -o "$work/none_analysis.h5"
contains "$work/err" "steps.h5: fewer than two samples in the window (--from 700 s)" "the window error names --from"
expect 2 "analyze of a window where nothing varies is a usage error" -- "$tcpmsim" analyze "$work/steps.h5" \
  --response muscle/force --from 0 --to 1 -o "$work/none_analysis.h5"
contains "$work/err" "in the window (--from 0 s --to 1 s)" "the window error names --from and --to"
# Issue 31: a window bound that is no finite time is refused, naming the option.
for bound in "--from nan" "--to nan" "--to inf" "--from -inf"; do
  expect 2 "analyze $bound is a usage error" -- "$tcpmsim" analyze "$work/steps.h5" \
    --response muscle/force --reference drive/power $bound -o "$work/none_analysis.h5"
  contains "$work/err" "${bound% *}: expected a time in s, a finite number, got '${bound#* }'" "the error names ${bound% *}"
done
[[ ! -e $work/none_analysis.h5 ]] && echo "ok: no analysis of a window that is none" || { echo "FAIL: an analysis file for a NaN window"; failures=$((failures + 1)); }

# Issue 31: recover refuses an HDF5 file that tcpmsim did not write, and writes nothing.
if /usr/bin/python3 -c "import h5py" 2>/dev/null; then
  /usr/bin/python3 -c 'import sys, h5py, numpy
with h5py.File(sys.argv[1], "w") as f:
    f.create_dataset("time", data=numpy.arange(5.0), maxshape=(None,), chunks=True)' "$work/foreign.h5.partial"
  expect 3 "recover of a foreign HDF5 file is a data-file error" -- "$tcpmsim" recover "$work/foreign.h5.partial"
  contains "$work/err" "$work/foreign.h5.partial: error: not a tcpmsim record: it has no 'tcpmsim_version' attribute" "the foreign file is named and why"
  [[ -e $work/foreign.h5.partial && ! -e $work/foreign.interrupted.h5 && ! -e $work/foreign.interrupted.h5.recovering ]] \
    && echo "ok: nothing recovered from a foreign file" || { echo "FAIL: recover wrote a record from a foreign file"; ls "$work"; failures=$((failures + 1)); }
  expect 3 "analyze of a foreign HDF5 file is a data-file error" -- "$tcpmsim" analyze "$work/foreign.h5.partial" \
    --response muscle/force -o "$work/none_analysis.h5"
  contains "$work/err" "$work/foreign.h5.partial: error: not a tcpmsim record: it has no 'tcpmsim_version' attribute" "analyze names the foreign file and why"
  rm -f "$work/foreign.h5.partial"
  # A record damaged inside (its /time a group): refused as a data-file error, not an internal one.
  /usr/bin/python3 -c 'import sys, h5py
with h5py.File(sys.argv[1], "w") as f:
    f.attrs["tcpmsim_version"] = "0.1.0"; f.attrs["config"] = "c"; f.create_group("time")' "$work/odd.h5.partial"
  expect 3 "recover of a record damaged inside is a data-file error" -- "$tcpmsim" recover "$work/odd.h5.partial"
  contains "$work/err" "$work/odd.h5.partial: error: cannot recover it: " "the damaged record is named"
  [[ -e $work/odd.h5.partial && ! -e $work/odd.interrupted.h5 && ! -e $work/odd.interrupted.h5.recovering ]] \
    && echo "ok: nothing recovered from a damaged record" || { echo "FAIL: recover left a file"; ls "$work"; failures=$((failures + 1)); }
  rm -f "$work/odd.h5.partial"
  # An attribute of many values where the reader takes one (an input's parameter, the seed) wrote
  # past its one value (a segmentation fault): refused as a damaged file.
  for attribute in "inputs/drive.power:initial:float" ":seed:uint64"; do
    IFS=: read -r where name type <<<"$attribute"
    cp "$work/run.h5" "$work/crafted.h5"
    /usr/bin/python3 -c 'import sys, h5py, numpy
with h5py.File(sys.argv[1], "a") as f:
    target = f[sys.argv[2] or "/"]
    if sys.argv[3] in target.attrs: del target.attrs[sys.argv[3]]
    target.attrs[sys.argv[3]] = numpy.arange(8000).astype(sys.argv[4])' "$work/crafted.h5" "$where" "$name" "$type"
    expect 3 "analyze of a record whose $name attribute holds 8000 values is a data-file error" -- \
      "$tcpmsim" analyze "$work/crafted.h5" --response muscle/force -o "$work/crafted_analysis.h5"
    contains "$work/err" "$work/crafted.h5: error: cannot read it as HDF5" "the crafted record is named"
  done
  rm -f "$work/crafted.h5"
fi

# export-fmu refuses what it cannot export as usage errors that say why (a scenario without an
# external input and an unknown --outputs were internal errors, exit 5; a --set of a parameter
# and a missing library, output errors, exit 4). A stand-in --library: the refusals come before
# anything is packed, and the sanitizer trees build no FMU library.
external="$source_dir/configs/ch7_control/external_force.yaml"
expect 2 "export-fmu without its library is a usage error" -- "$tcpmsim" export-fmu "$external" \
  --library "$work/none.so" -o "$work/x.fmu"
contains "$work/err" "--library: no FMU library at $work/none.so" "the missing library is named"
expect 2 "export-fmu of a scenario without an external input is a usage error" -- "$tcpmsim" \
  export-fmu "$config" --library "$external" -o "$work/x.fmu"
contains "$work/err" "has no external input for an FMU's master to set (a controller section of type external)" "the export says what the scenario lacks"
expect 2 "export-fmu of an output the scenario does not record is a usage error" -- "$tcpmsim" \
  export-fmu "$external" --library "$external" --outputs muscle.colour -o "$work/x.fmu"
contains "$work/err" "--outputs: no recorded output 'muscle.colour' in 'ch7_external_force'; it records: muscle.thermal_force" "the unknown output is named beside those recorded"
expect 2 "export-fmu with a --set of a model parameter is a usage error" -- "$tcpmsim" \
  export-fmu "$external" --library "$external" --set "muscle.mechanics.k1=10 N/m" -o "$work/x.fmu"
contains "$work/err" "--set of model parameters (muscle.mechanics.k1) is not carried into an FMU" "the parameter's --set is named"
expect 2 "export-fmu of an output named twice is a usage error" -- "$tcpmsim" export-fmu "$external" \
  --library "$external" --outputs load.force,load.force -o "$work/x.fmu"
contains "$work/err" "--outputs: 'load.force' is named twice" "the output named twice is named"
expect 2 "export-fmu of an external input as an output is a usage error" -- "$tcpmsim" export-fmu \
  "$external" --library "$external" --outputs controller.power_command -o "$work/x.fmu"
contains "$work/err" "--outputs: 'controller.power_command' is an external input, a variable of the FMU already" "the input given as an output is named"
mkdir -p "$work/relative"
sed 's|^load: .*|load: {type: deflection, deflection: {type: data, file: deflection.csv, channel: deflection}}|' \
  "$external" >"$work/relative/data_load.yaml"
printf 'time[s],deflection[mm]\n0,20\n200,20\n' >"$work/relative/deflection.csv"
expect 0 "a scenario that reads a data file beside it is valid" -- "$tcpmsim" validate "$work/relative/data_load.yaml"
expect 2 "export-fmu of a scenario reading a file by a relative path is a usage error" -- "$tcpmsim" \
  export-fmu "$work/relative/data_load.yaml" --library "$external" -o "$work/x.fmu"
contains "$work/err" "$work/relative/data_load.yaml: it reads a file by a relative path (a measurement or a data signal), which the FMU does not carry" "the export says why it cannot carry the scenario"
[[ ! -e $work/x.fmu ]] && echo "ok: no FMU after a refusal" || { echo "FAIL: an FMU written after a refusal"; failures=$((failures + 1)); }
# A control character in the scenario's name (a --set may carry one) is written into the
# description as text: XML 1.0 cannot hold it (it was an internal error).
expect 0 "export-fmu of a name with a control character" -- "$tcpmsim" export-fmu "$external" \
  --library "$external" --set $'scenario.name="bell\x07<&>"' -o "$work/bell.fmu" --quiet
expect 0 "its description holds the name as text" -- /usr/bin/python3 -c '
import sys, zipfile
text = zipfile.ZipFile(sys.argv[1]).read("modelDescription.xml").decode()
sys.exit(0 if "modelName=\"bell\\x07&lt;&amp;&gt;\"" in text else text[:300])' "$work/bell.fmu"
cp "$discover/ch7_bench.yaml" "$work/own_bench.yaml"
expect 2 "measure -o its own bench file is a usage error" -- "$tcpmsim" measure "$discover/ch7_base.yaml" \
  --set "measurement.file=$work/bench.h5" --bench "$work/own_bench.yaml" -o "$work/own_bench.yaml"
cmp -s "$discover/ch7_bench.yaml" "$work/own_bench.yaml" && echo "ok: the bench file is untouched" || { echo "FAIL: measure replaced its bench file"; failures=$((failures + 1)); }
# measure: a run the solver cannot finish is a simulation failure (exit 1), and no file, not
# even the empty partial file of the output check, is left (it was an output error, exit 4).
expect 1 "a measurement whose run fails exits 1" -- "$tcpmsim" measure "$discover/ch7_base.yaml" \
  --set "measurement.file=$work/bench.h5" --set solver.max_steps=1 --bench "$discover/ch7_bench.yaml" \
  -o "$work/failed.csv"
contains "$work/err" "tcpmsim: simulation failed: more than 1 solver steps" "the failed measurement says why"
[[ ! -e $work/failed.csv && ! -e $work/failed.csv.partial ]] && echo "ok: nothing left by a failed measurement" \
  || { echo "FAIL: a failed measurement left a file"; ls "$work"; failures=$((failures + 1)); }

check_provenance

if /usr/bin/python3 -c "import h5py, matplotlib" 2>/dev/null; then
  expect 0 "the plot tool reads the record" -- "$source_dir/tools/tcpmsim-plot" traces "$work/run.h5" -o "$work/run.png"
  expect 1 "the plot tool names a channel the record lacks" -- "$source_dir/tools/tcpmsim-plot" traces "$work/run.h5" --channels muscle/colour -o "$work/none.png"
  contains "$work/err" "none of the channels muscle/colour is in $work/run.h5" "the plot error names the channel and the file"
  expect 1 "a record is not a control-tasks file" -- "$source_dir/tools/tcpmsim-plot" bode "$work/run.h5" -o "$work/none.png"
  contains "$work/err" "holds the sweep tasks (none)" "the plot error says what the file holds"
  expect 1 "the plot tool names an output it cannot write" -- "$source_dir/tools/tcpmsim-plot" traces "$work/run.h5" -o "$work/none/run.png"
  contains "$work/err" "tcpmsim-plot: cannot write $work/none/run.png: No such file or directory" "the plot error names the output, not a traceback"
  expect 1 "the plot tool refuses a dataset that is no trace over time" -- "$source_dir/tools/tcpmsim-plot" traces "$work/run.h5" \
    --channels inputs/drive.power/times -o "$work/none.png"
  contains "$work/err" "none of the channels inputs/drive.power/times is in $work/run.h5 as a trace over its time" "the plot error says what the channel is not"
  [[ -s $work/run.png ]] && echo "ok: plot written" || { echo "FAIL: no plot"; failures=$((failures + 1)); }
fi

echo "$failures failure(s)"
exit $((failures > 0))
