# Sourced by scripts/test.sh and scripts/fuzz.sh: the options every sanitizer run uses. Leaks are
# errors, except those tests/lsan.supp names as a library's own (udunits2's unit parser).
export ASAN_OPTIONS=detect_leaks=1
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
