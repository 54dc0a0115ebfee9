#!/usr/bin/env bash
# Mutation testing with hand-written mutants: each scripts/mutants/*.patch is
# one small wrong change to the core (lib/), the planning layers
# (planners/) or the soundness suite's cases (benchmarks/soundness/), the
# kind of bug a test must catch (a flipped comparison, a wrong sign, a
# tolerance widened, an enlargement halved, a check removed, a case that no
# longer has the geometry it is named for). For each one
# the script applies it, rebuilds, runs the ctest subset named on the
# patch's "# tests:" line (ctest arguments, e.g. "-L core") and reverts it;
# a mutant is killed when at least one test fails, and survives otherwise.
# It prints every mutant's verdict and exits 1 when one survived: a
# surviving mutant needs a new test (or, when it is equivalent to the
# original, its removal from the list).
#
#   scripts/mutants.sh [-B build-dir] [-j jobs] [mutant.patch ...]
#
# Default: every mutant, in build/release (configured as the README's
# release build), with 2 jobs. Slow (a rebuild and a test run per mutant):
# run it with the long sweeps, not in CI. The working tree's mutated files
# must be clean; an interrupted run reverts the mutant it was testing.
# A new mutant: edit the source, `git diff > scripts/mutants/<name>.patch`,
# revert the source, and put the "# tests:" line (and a "# " line saying
# what the mutant breaks) above the diff.
set -euo pipefail
cd "$(dirname "$0")/.."

build=build/release
jobs=2
while getopts "B:j:" opt; do
  case $opt in
    B) build=$OPTARG ;;
    j) jobs=$OPTARG ;;
    *) echo "usage: $0 [-B build-dir] [-j jobs] [mutant.patch ...]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
if [ $# -gt 0 ]; then mutants=("$@"); else mutants=(scripts/mutants/*.patch); fi
[ -f "$build/CMakeCache.txt" ] || { echo "$0: $build is not a configured build directory" >&2; exit 2; }

applied=""
revert() { if [ -n "$applied" ]; then git apply -R "$applied"; applied=""; fi; }
trap revert EXIT INT TERM

log=$(mktemp -d)
survived=()
for m in "${mutants[@]}"; do
  name=$(basename "$m" .patch)
  read -r -a tests <<<"$(sed -n 's/^# tests: //p' "$m" | head -1)"
  if ! git apply --check "$m" 2>/dev/null; then
    echo "$name: DOES NOT APPLY (the source changed: update the patch)"
    survived+=("$name")
    continue
  fi
  git apply "$m"
  applied=$m
  if ! cmake --build "$build" -j "$jobs" >"$log/$name.build" 2>&1; then
    echo "$name: killed (does not build; $log/$name.build)"
  elif ctest --test-dir "$build" -j "$jobs" "${tests[@]}" >"$log/$name.ctest" 2>&1; then
    echo "$name: SURVIVED (ctest ${tests[*]} passes)"
    survived+=("$name")
  else
    failed=$(grep -cE '^\s+[0-9]+ - .* \((Failed|Timeout|SEGFAULT|Subprocess aborted|Exception)' "$log/$name.ctest" || true)
    echo "$name: killed ($failed failing tests of ctest ${tests[*]})"
  fi
  revert
done
# Rebuild the unmutated sources, so the build directory is left as found.
cmake --build "$build" -j "$jobs" >"$log/final.build" 2>&1 || echo "$0: the final rebuild failed: $log/final.build"
echo "${#mutants[@]} mutants, ${#survived[@]} survived${survived:+: ${survived[*]}} (logs in $log)"
[ ${#survived[@]} -eq 0 ]
