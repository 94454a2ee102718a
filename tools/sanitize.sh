#!/usr/bin/env bash
# Builds the unit tests (and the command they run) with AddressSanitizer and
# UndefinedBehaviorSanitizer in build-asan/ and runs them (ctest -L unit), all but the long runs
# (tests/support/long_run.hpp), which the README's test command runs in the Release build.
set -euo pipefail
cd "$(dirname "$0")/.."
# Line tables only (-g1): the sanitizers' reports name file and line; full debug info would
# lengthen the build.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DSANDCASTLE_SANITIZE=ON >/dev/null
cmake --build build-asan -j"$(nproc)" --target unit_tests
cd build-asan
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -L unit
