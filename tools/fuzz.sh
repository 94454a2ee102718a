#!/usr/bin/env bash
# Builds the libFuzzer targets (clang++, ASan + UBSan, in build-fuzz/) and runs each for a bounded
# time (FUZZ_SECONDS, default 60) from its seed corpus tests/fuzz/corpus/<target>/. A crash fails
# the script and leaves the input as build-fuzz/<target>-crash-*: add it to the seed corpus (the
# unit suite `fuzz_corpus` then replays it as a regression test) and fix the bug.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-60}"
targets=(case_loader obj_loader)
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSANDCASTLE_FUZZ=ON -DSANDCASTLE_SANITIZE=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]/#/fuzz_}"
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus-$t"
  rm -f "build-fuzz/$t-"*
  echo "fuzzing $t for ${seconds} s"
  "build-fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/$t-" "build-fuzz/corpus-$t" "tests/fuzz/corpus/$t" 2>&1 |
    grep -E "^#[0-9]+.*DONE|stat::number_of_executed_units|ERROR|SUMMARY|Test unit written" || true
  if ls "build-fuzz/$t-"crash-* "build-fuzz/$t-"timeout-* "build-fuzz/$t-"oom-* >/dev/null 2>&1; then
    echo "fuzz_$t found a failing input: $(ls "build-fuzz/$t-"*)"
    exit 1
  fi
done
