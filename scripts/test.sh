#!/usr/bin/env bash
# Fresh Debian 12 to a passing test suite: installs, builds (warnings are errors) and runs
# every test through ctest.
#   TCPMSIM_SANITIZE=ON   build and test under AddressSanitizer + UndefinedBehaviorSanitizer
#   TCPMSIM_BUILD_DIR     build directory (default build, or build-sanitize)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
sanitize="${TCPMSIM_SANITIZE:-OFF}"
build_dir="${TCPMSIM_BUILD_DIR:-$([[ $sanitize == ON ]] && echo build-sanitize || echo build)}"
build_type=$([[ $sanitize == ON ]] && echo RelWithDebInfo || echo Release)
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" -DTCPMSIM_SANITIZE="$sanitize" -DTCPMSIM_BUILD_TESTS=ON
cmake --build "$build_dir" -j"$(nproc)"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)"
