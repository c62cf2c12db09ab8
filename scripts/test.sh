#!/usr/bin/env bash
# Fresh Debian 12 to a passing test suite: installs, builds (warnings are errors) and runs
# every test through ctest.
#   TCPMSIM_SANITIZE=ON       build and test under AddressSanitizer + UndefinedBehaviorSanitizer
#   TCPMSIM_SANITIZE=thread   build and test under ThreadSanitizer
#   TCPMSIM_BUILD_DIR         build directory (default build, build-sanitize or build-tsan)
#   TCPMSIM_TEST_FILTER       only the tests whose names match this regular expression
#   TCPMSIM_BUILD_TARGETS     only these targets (default: all, benchmarks included)
#   TCPMSIM_TEST_FILES        only these test files of tests/ (a ;-list) in tcpmsim_tests
#   TCPMSIM_TEST_EXCLUDE_FILES  these test files of tests/ (a ;-list) left out of tcpmsim_tests
#   TCPMSIM_TEST_EXCLUDE      leave out the tests whose names match this regular expression
#   TCPMSIM_FUZZ=ON           also build the libFuzzer targets and test their regression inputs
#                             (clang; scripts/fuzz.sh can then fuzz this tree)
#   TCPMSIM_FUZZ_COVERAGE     full (libFuzzer's, the default) or counters (edge counters only: the
#                             suite runs as fast as without, so one ASan tree serves both)
# The sanitizer trees are compiled with clang unless CC and CXX say otherwise: the ASan tree
# builds in 414 s against GCC's 880 s (a test file in 11.5 s against 20.2 s), runs its suite
# nearly as fast (ctest 455 s against 404 s), and its records are bit-identical to the pinned
# ones. CC and CXX are read when a tree is first configured; an existing tree keeps its compiler.
# A new tree is generated for Ninja (unless CMAKE_GENERATOR says otherwise; an existing tree keeps
# its generator): it compiles a library's files while the one before it is still building, which
# Make does not, and built the ASan tree, fuzz targets included, in 326 s against Make's 404 s
# without them.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
export CMAKE_GENERATOR="${CMAKE_GENERATOR:-Ninja}"
sanitize="${TCPMSIM_SANITIZE:-OFF}"
case $sanitize in
  OFF) default_dir=build; build_type=Release ;;
  thread) default_dir=build-tsan; build_type=RelWithDebInfo ;;
  *) default_dir=build-sanitize; build_type=RelWithDebInfo ;;
esac
build_dir="${TCPMSIM_BUILD_DIR:-$default_dir}"
if [[ ($sanitize != OFF || ${TCPMSIM_FUZZ:-OFF} == ON) && -z ${CXX:-} ]]; then
  export CC=clang CXX=clang++
fi
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" -DTCPMSIM_SANITIZE="$sanitize" -DTCPMSIM_BUILD_TESTS=ON \
  -DTCPMSIM_FUZZ="${TCPMSIM_FUZZ:-OFF}" -DTCPMSIM_FUZZ_COVERAGE="${TCPMSIM_FUZZ_COVERAGE:-full}" \
  -DTCPMSIM_TEST_FILES="${TCPMSIM_TEST_FILES:-}" \
  -DTCPMSIM_TEST_EXCLUDE_FILES="${TCPMSIM_TEST_EXCLUDE_FILES:-}"
cmake --build "$build_dir" -j"$(nproc)" ${TCPMSIM_BUILD_TARGETS:+--target $TCPMSIM_BUILD_TARGETS}
source scripts/sanitizer_options.sh
ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" ${TCPMSIM_TEST_FILTER:+-R "$TCPMSIM_TEST_FILTER"} \
  ${TCPMSIM_TEST_EXCLUDE:+-E "$TCPMSIM_TEST_EXCLUDE"}
