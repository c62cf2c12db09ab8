#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (build-fuzz: ASan + UBSan + coverage) and runs each
# for a bounded time, seeded from the shipped inputs: the scenario loader from configs/ (and a
# few --set seeds), the measured-data CSV reader and the coil-sequence reader from data files,
# the fit file with its data from fuzz/seeds/fuzz_fit/, the sweep file from configs/sweeps/.
# New inputs that widen coverage go to build-fuzz/corpus/<target>; a crash, leak, hang (timeout)
# or out-of-memory stops the script with the input saved as build-fuzz/<target>-crash-* (-leak-,
# -timeout-, -oom-) and printed in base64, to become a regression input in fuzz/regressions/.
#   scripts/fuzz.sh [SECONDS_PER_TARGET (default 60)] [-- extra libFuzzer options]
#   scripts/fuzz.sh 0 -runs=1000000   # a million executions per target
# TCPMSIM_FUZZ_SECONDS="fuzz_coil_sequence=20 ..." gives a target a time of its own. The targets
# run one per core, the slowest to fuzz first, so two short ones can share the last core.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
[[ ${1:-} == -- ]] && shift
scripts/install-deps.sh
export CMAKE_GENERATOR="${CMAKE_GENERATOR:-Ninja}"  # new trees only, as scripts/test.sh
# TCPMSIM_FUZZ_BUILD_DIR: a tree already configured with TCPMSIM_FUZZ=ON (e.g. one built by
# `CC=clang CXX=clang++ TCPMSIM_FUZZ=ON scripts/test.sh`); by default build-fuzz, configured here.
build=${TCPMSIM_FUZZ_BUILD_DIR:-build-fuzz}
if [[ ! -f $build/CMakeCache.txt ]]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTCPMSIM_FUZZ=ON \
    -DTCPMSIM_BUILD_TESTS=OFF >/dev/null
elif ! grep -q '^TCPMSIM_FUZZ:BOOL=ON' "$build/CMakeCache.txt"; then
  echo "fuzz: $build is not configured with TCPMSIM_FUZZ=ON" >&2
  exit 2
fi
targets=(fuzz_scenario fuzz_fit fuzz_sweep fuzz_measured_csv fuzz_coil_sequence)
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"

seeds() {  # the seed directory of a target, made afresh from the repository's inputs
  local target=$1 dir=$build/seeds/$1
  rm -rf "$dir" && mkdir -p "$dir"
  case $target in
    fuzz_scenario)
      find configs -name '*.yaml' -exec cp --backup=numbered -t "$dir" {} +
      printf '#set muscle.mechanics.k1=12 N/m\n' | cat - configs/ch7_identification.yaml >"$dir/set_parameter.yaml"
      printf '#set load={type: hanging_mass, mass: 35 g}\n' | cat - configs/ch7_identification.yaml >"$dir/set_section.yaml"
      printf '#set ..\n' | cat - configs/ch7_identification.yaml >"$dir/set_dots.yaml" ;;
    fuzz_measured_csv)
      cp tests/data/measured/*.csv "$dir" 2>/dev/null || true
      printf 'time[s],power[W],deflection[mm],force[N]\n0,0.1,20,0.1\n0.0625,0.2,20.5,0.11\n' >"$dir/minimal.csv" ;;
    fuzz_coil_sequence)
      find data/coil-spring-inductance -name '*.csv' | head -n 5 | xargs -r cp -t "$dir" ;;
    fuzz_fit)  # the fit file, "#data", then its measurement (fuzz/seeds/: 30 s of the ch. 7 bench)
      cp fuzz/seeds/fuzz_fit/* "$dir"
      { grep -v '^#' configs/discover/ch7_fit.yaml; } >"$dir/no_data.yaml" ;;
    fuzz_sweep)
      grep -l '^sweep:' configs/sweeps/*.yaml | xargs -r cp -t "$dir" ;;
  esac
  echo "$dir"
}

# -timeout=60: the magnetic bundle (configs/bundle/magnetic_coupling.yaml) computes its mutual
# inductances when it loads, 0.06 s in Release and 0.2 s instrumented (6 s before the single-
# integral ring formula).
# fuzz/regressions/<target> holds every input fuzzing has found to fail: each is run first.
# scripts/sanitizer_options.sh sets the sanitizers' options, with tests/lsan.supp.
source scripts/sanitizer_options.sh
seconds_of() {  # a target's time: its entry in TCPMSIM_FUZZ_SECONDS, or SECONDS_PER_TARGET
  local entry
  for entry in ${TCPMSIM_FUZZ_SECONDS:-}; do
    [[ ${entry%%=*} == "$1" ]] && { echo "${entry#*=}"; return; }
  done
  echo "$seconds"
}
fuzz_one() {  # fuzzes one target for its time; its log is $build/<target>.log
  local target=$1 corpus=$build/corpus/$1 seed_dir regressions=() budget
  budget=$(seconds_of "$target")
  mkdir -p "$corpus"
  seed_dir=$(seeds "$target")
  [[ -d fuzz/regressions/$target ]] && regressions=("fuzz/regressions/$target")
  rm -f "$build/$target-"{crash,leak,timeout,oom}-*
  echo "fuzz: $target for ${budget} s ($(ls "$seed_dir" | wc -l) seeds, $(ls "$corpus" | wc -l) in the corpus)"
  "$build/fuzz/$target" "$corpus" "$seed_dir" "${regressions[@]}" -max_total_time="$budget" \
    -max_len=65536 -timeout=60 -rss_limit_mb=2048 -artifact_prefix="$build/$target-" \
    -print_final_stats=1 "${fuzz_options[@]}" >"$build/$target.log" 2>&1 || true
}
# One target per core at a time: each libFuzzer process is single-threaded, so on two cores the
# five targets take three rounds of their time instead of five.
fuzz_options=("$@")
for target in "${targets[@]}"; do
  while (($(jobs -rp | wc -l) >= $(nproc))); do wait -n || true; done
  fuzz_one "$target" &
done
wait
for target in "${targets[@]}"; do
  log=$build/$target.log
  echo "fuzz: $target:"
  grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss)|Done [0-9]+ runs" "$log" || true
  # A crash, a leak, a hang or running out of memory fails; a slow input (slow-unit) does not.
  for kind in crash leak timeout oom; do
    if compgen -G "$build/$target-$kind-*" >/dev/null; then
      artifact=$(ls "$build/$target-$kind-"* | head -n 1)
      grep -A 40 -E "==[0-9]+==ERROR|runtime error|Sanitizer" "$log" | head -n 60 >&2 || true
      echo "fuzz: $target: $kind; the input: $artifact (base64: $(base64 -w0 "$artifact"))" >&2
      echo "fuzz: add it to fuzz/regressions/$target/ once fixed" >&2
      exit 1
    fi
  done
done
echo "fuzz: no crash"
