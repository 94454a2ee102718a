#!/usr/bin/env bash
# Mutation check: applies each small physics mutation of tests/mutations/mutations.tsv (a sign, a
# factor, an index, a dropped term) to a scratch git worktree of HEAD, builds the unit tests, runs
# them and reports whether the tests caught the mutation (build error or failing test) or it
# survived. Not part of CI: one build per mutation.
#
# Usage: tests/mutations/run.sh [--only ID,ID,...] [--tests BOOST_RUN_TEST_FILTER] [--timeout SECONDS]
#   --tests  passed to unit_tests --run_test (default: all suites)
# Exit code: 0 when every applied mutation was caught, 1 otherwise.
set -euo pipefail

repo=$(git rev-parse --show-toplevel)
manifest="$repo/tests/mutations/mutations.tsv"
only="" tests="" timeout_s=900
while [[ $# -gt 0 ]]; do
  case "$1" in
    --only) only="$2"; shift 2 ;;
    --tests) tests="$2"; shift 2 ;;
    --timeout) timeout_s="$2"; shift 2 ;;
    *) echo "usage: $0 [--only ID,...] [--tests FILTER] [--timeout S]" >&2; exit 2 ;;
  esac
done

scratch=$(mktemp -d /tmp/sandcastle_mutations.XXXXXX)
git -C "$repo" worktree add --detach "$scratch/src" HEAD >/dev/null
cleanup() { git -C "$repo" worktree remove --force "$scratch/src" >/dev/null 2>&1 || true; rm -rf "$scratch"; }
trap cleanup EXIT
src="$scratch/src" build="$scratch/src/build"

run_tests() {
  local args=(--log_level=nothing --report_level=no)
  [[ -n "$tests" ]] && args+=(--run_test="$tests")
  (cd "$src" && timeout "$timeout_s" "$build/unit_tests" "${args[@]}" >/dev/null 2>&1)
}
build_tests() { cmake --build "$build" --target unit_tests -j2 >"$scratch/build.log" 2>&1; }

cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache >/dev/null
build_tests || { echo "baseline does not build (see $scratch/build.log)" >&2; exit 2; }
run_tests || { echo "baseline unit tests fail: fix them before a mutation check" >&2; exit 2; }

caught=0 survived=0 skipped=0 survivors=()
while IFS=$'\t' read -r id file from to; do
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
  if ! build_tests; then verdict="CAUGHT    $id (does not build)"; caught=$((caught + 1))
  elif ! run_tests; then verdict="CAUGHT    $id"; caught=$((caught + 1))
  else verdict="SURVIVED  $id"; survived=$((survived + 1)); survivors+=("$id"); fi
  echo "$verdict"
  git -C "$src" checkout -- "$file"
done <"$manifest"

total=$((caught + survived))
echo "caught $caught of $total applied mutations ($skipped skipped)"
[[ ${#survivors[@]} -gt 0 ]] && echo "survivors: ${survivors[*]}"
[[ $survived -eq 0 ]]
