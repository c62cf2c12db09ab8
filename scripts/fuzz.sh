#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (build-fuzz: ASan + UBSan + coverage) and runs each
# for a bounded time, seeded from the shipped inputs: the scenario loader from configs/ (and a
# few --set seeds), the measured-data CSV reader and the coil-sequence reader from data files.
# New inputs that widen coverage go to build-fuzz/corpus/<target>; a crash, leak, hang (timeout)
# or out-of-memory stops the script with the input saved as build-fuzz/<target>-crash-* (-leak-,
# -timeout-, -oom-), to become a regression test.
#   scripts/fuzz.sh [SECONDS_PER_TARGET (default 60)] [-- extra libFuzzer options]
#   scripts/fuzz.sh 0 -runs=1000000   # a million executions per target
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
[[ ${1:-} == -- ]] && shift
scripts/install-deps.sh
build=build-fuzz
CC=clang CXX=clang++ cmake -S . -B $build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTCPMSIM_FUZZ=ON \
  -DTCPMSIM_BUILD_TESTS=OFF >/dev/null
targets=(fuzz_scenario fuzz_measured_csv fuzz_coil_sequence)
cmake --build $build -j"$(nproc)" --target "${targets[@]}"

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
  esac
  echo "$dir"
}

# -timeout=60: the magnetic bundle (configs/bundle/magnetic_coupling.yaml) computes its mutual
# inductances when it loads, 0.6 s in Release and over 10 s instrumented.
for target in "${targets[@]}"; do
  corpus=$build/corpus/$target
  mkdir -p "$corpus"
  seed_dir=$(seeds "$target")
  echo "fuzz: $target for ${seconds} s ($(ls "$seed_dir" | wc -l) seeds, $(ls "$corpus" | wc -l) in the corpus)"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/fuzz/$target" "$corpus" "$seed_dir" -max_total_time="$seconds" -max_len=65536 \
    -timeout=60 -rss_limit_mb=2048 -artifact_prefix="$build/$target-" -print_final_stats=1 "$@" \
    2>&1 | grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss|==[0-9]+==|SUMMARY|fuzz:)|Done [0-9]+ runs" || true
  # A crash, a leak, a hang or running out of memory fails; a slow input (slow-unit) does not.
  for kind in crash leak timeout oom; do
    if compgen -G "$build/$target-$kind-*" >/dev/null; then
      echo "fuzz: $target: $kind; the input: $(ls "$build/$target-$kind-"*)" >&2
      exit 1
    fi
  done
done
echo "fuzz: no crash"
