#!/usr/bin/env bash
# Mutation check: applies each small physics mutation of tests/mutations/mutations.tsv (a sign, a
# factor, an index, a dropped term) to a scratch git worktree of HEAD, builds, and runs the unit
# tests: first the suites the list names for the mutated code, one test case at a time up to the
# first that fails, then, if they pass, every CTest unit suite (two at a time, stopping at the first
# failure); a mutation the unit tests miss then meets the quick validation tier (its gates and the
# regression limits of the blessed baselines). It reports whether the mutation was caught (build
# error, failing test, failed gate or regression) and by what (a run that outlasts --timeout, as a
# hanging mutation does, is named as caught by the time limit), or that it survived. Not part of CI:
# one build per mutation (ccache, where installed, shortens the rebuilds).
#
# Usage: tests/mutations/run.sh [--only ID,ID,...] [--tests BOOST_RUN_TEST_FILTER] [--no-suite] [--timeout SECONDS]
#   --tests     run only these unit tests (unit_tests --run_test filter) instead of every suite
#   --no-suite  do not run the quick validation tier on survivors of the unit tests
# Exit code: 0 when every applied mutation was caught, 1 otherwise.
set -euo pipefail

repo=$(git rev-parse --show-toplevel)
manifest="$repo/tests/mutations/mutations.tsv"
only="" tests="" suite=1 timeout_s=900
while [[ $# -gt 0 ]]; do
  case "$1" in
    --only) only="$2"; shift 2 ;;
    --tests) tests="$2"; shift 2 ;;
    --no-suite) suite=0; shift ;;
    --timeout) timeout_s="$2"; shift 2 ;;
    *) echo "usage: $0 [--only ID,...] [--tests FILTER] [--no-suite] [--timeout S]" >&2; exit 2 ;;
  esac
done

scratch=$(mktemp -d /tmp/sandcastle_mutations.XXXXXX)
git -C "$repo" worktree add --detach "$scratch/src" HEAD >/dev/null
cleanup() { git -C "$repo" worktree remove --force "$scratch/src" >/dev/null 2>&1 || true; rm -rf "$scratch"; }
trap cleanup EXIT
src="$scratch/src" build="$scratch/src/build"

# The unit tests of the --run_test filter $1 (a mutation's own suites, or --tests).
run_filter() {
  local rc=0
  (cd "$src" && timeout "$timeout_s" "$build/unit_tests" --run_test="$1" --log_level=nothing --report_level=no >/dev/null 2>&1) || rc=$?
  note_timeout $rc
}
# Passes on the exit code $1 of a run under `timeout`, and sets timed_out when it was the timeout's
# (124): a mutation that makes a run hang is caught, but by the time limit, not by a check, and a
# baseline that outlasts the limit is a busy machine, not a failing test.
timed_out=0
note_timeout() {
  [[ $1 -eq 124 ]] && timed_out=1
  return "$1"
}
# A mutation's own suites ($1, suite names joined by ':'), one test case at a time, stopping at the
# first that fails: Boost.Test runs every case of a suite even after one has failed, and a slow
# suite (MPM, DEM) would otherwise cost its whole run for a mutation its first case catches. The
# cases are listed once, from the unmutated build (list_cases).
run_own_suites() {
  local suite case
  for suite in ${1//:/ }; do
    for case in ${cases[$suite]:-}; do run_filter "$suite/$case" || return 1; done
    [[ -n "${cases[$suite]:-}" ]] || run_filter "$suite" || return 1
  done
}
declare -A cases
# Fills `cases`: for every top-level suite, its test cases' names (Boost.Test --list_content).
list_cases() {
  local suite="" line
  while IFS= read -r line; do
    if [[ "$line" =~ ^([A-Za-z0-9_]+)\*?$ ]]; then suite="${BASH_REMATCH[1]}"
    elif [[ -n "$suite" && "$line" =~ ^\ {4}([A-Za-z0-9_]+)\*$ ]]; then cases[$suite]+="${BASH_REMATCH[1]} "; fi
  done < <("$build/unit_tests" --list_content 2>&1)
}
run_tests() {
  if [[ -n "$tests" ]]; then run_filter "$tests"; return; fi
  local rc=0
  (cd "$build" && timeout "$timeout_s" ctest -L unit -j2 --stop-on-failure >"$scratch/unit.log" 2>&1) || rc=$?
  note_timeout $rc
}
# The quick validation tier of the mutated code against the gates and the blessed baselines.
run_suite() {
  local rc=0
  timeout "$timeout_s" "$build/sandcastle" validate --tier quick --root "$src" --out "$scratch/suite" --no-plots \
    >"$scratch/suite.log" 2>&1 || rc=$?
  note_timeout $rc
}
build_tests() { cmake --build "$build" -j2 >"$scratch/build.log" 2>&1; }

# ccache, where installed, makes the one-file rebuilds of the mutations faster; the check needs none.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
build_tests || { echo "baseline does not build (see $scratch/build.log)" >&2; exit 2; }
list_cases
# The baseline must pass within the limit that each mutation's runs get.
baseline_fails() {
  if [[ $timed_out -eq 1 ]]; then echo "baseline $1 take longer than --timeout $timeout_s s: run on an idle machine or raise it" >&2
  else echo "baseline $1 fail: fix them before a mutation check" >&2; fi
  grep -hE "\*\*\*|[Ff]ailed|error:" "$scratch/unit.log" "$scratch/suite.log" 2>/dev/null | head -20 >&2
  exit 2
}
run_tests || baseline_fails "unit tests"
if [[ $suite -eq 1 ]]; then
  run_suite || baseline_fails "quick tier cases (see $scratch/suite.log)"
fi

caught=0 survived=0 skipped=0 survivors=()
while IFS=$'\t' read -r -u 3 id file from to own; do
  [[ -z "$id" || "$id" == \#* ]] && continue
  [[ -n "$only" && ",$only," != *",$id,"* ]] && continue
  if ! python3 - "$src/$file" "$from" "$to" <<'PY'
import sys
path, old, new = sys.argv[1], sys.argv[2].replace("\\n", "\n"), sys.argv[3].replace("\\n", "\n")
text = open(path).read()
if text.count(old) != 1:
    sys.exit(1)
open(path, "w").write(text.replace(old, new))
PY
  then
    echo "SKIPPED   $id ($file: text not found exactly once)"; skipped=$((skipped + 1)); continue
  fi
  timed_out=0
  if ! build_tests; then verdict="CAUGHT    $id (does not build)"; caught=$((caught + 1))
  elif [[ -z "$tests" && -n "$own" ]] && ! run_own_suites "$own"; then verdict="CAUGHT    $id (unit tests: $own)"; caught=$((caught + 1))
  elif ! run_tests; then verdict="CAUGHT    $id (unit tests)"; caught=$((caught + 1))
  elif [[ $suite -eq 1 ]] && ! run_suite; then verdict="CAUGHT    $id (quick tier)"; caught=$((caught + 1))
  else verdict="SURVIVED  $id"; survived=$((survived + 1)); survivors+=("$id"); fi
  [[ $timed_out -eq 1 && "$verdict" == CAUGHT* ]] && verdict+=" by the time limit of $timeout_s s"
  echo "$verdict"
  git -C "$src" checkout -- "$file"
done 3<"$manifest"  # fd 3: the tests (mpirun among them) may read standard input

total=$((caught + survived))
echo "caught $caught of $total applied mutations ($skipped skipped)"
[[ ${#survivors[@]} -gt 0 ]] && echo "survivors: ${survivors[*]}"
[[ $survived -eq 0 ]]
