#!/usr/bin/env bash
# The quick part of the test suite (ctest -LE slow) under AddressSanitizer and
# UndefinedBehaviorSanitizer: a sanitized build of the project's own code in build-sanitize/
# (-O1, as ASan advises), then its tests. Any invalid access, leak or undefined behaviour fails
# the test that caused it. CI runs it after the Release suite (the README's test command).
# Leaks inside libraries ReliefLab does not build are suppressed by name
# (tests/sanitizer-suppressions.txt).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=None -DCMAKE_C_FLAGS=-O1 -DCMAKE_CXX_FLAGS=-O1 \
  -DRELIEFLAB_SANITIZE=ON -DRELIEFLAB_BUILD_BENCHMARKS=OFF
cmake --build build-sanitize -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer-suppressions.txt"
export UBSAN_OPTIONS=print_stacktrace=1
ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)" -LE slow
