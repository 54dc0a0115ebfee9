#!/usr/bin/env bash
# Builds mddual and runs the whole test suite (this is what CI runs):
#   1. Release build of everything, all ctest tests (core, CLI, install);
#   2. the core tests again under AddressSanitizer + UndefinedBehaviorSanitizer;
#   3. the OMPL layer's concurrency test under ThreadSanitizer;
#   4. the libFuzzer targets, a fixed number of executions each (scripts/fuzz.sh);
#   5. the clang-format check.
# Set MDDUAL_JOBS to change the parallelism (default: all cores).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh

jobs="${MDDUAL_JOBS:-$(nproc)}"
# Each phase prints its wall time when the next begins (the suite's budget is
# 20 minutes with the builds; docs/results/fresh-clones.md records them).
phase_name=""
phase_start=$SECONDS
phase() {
  [ -n "$phase_name" ] && echo "-- $phase_name: $((SECONDS - phase_start)) s"
  phase_name="$1"
  phase_start=$SECONDS
  [ -n "$1" ] && echo "== $1"
  return 0
}
phase "release build and all tests"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DMDDUAL_WARNINGS_AS_ERRORS=ON
cmake --build build/release -j "$jobs"
ctest --test-dir build/release --output-on-failure -j "$jobs"

# The instrumented builds' flags (-O1, line tables): scripts/instrumented-flags.sh.
source scripts/instrumented-flags.sh
san_flags="$instrumented_flags"

# Both sanitizer builds use Clang (as the fuzz targets do): on the 2-core
# machine it compiled the ASan + UBSan core tests in 24% less CPU time than
# GCC with the tests as fast, and the TSan test ran in 7.5 s instead of 24 s.
# And Ninja: it compiles the tests while the library they link is still being
# built, where Make waits (the fuzz build: 149 s -> 107 s).
phase "core tests under address + undefined sanitizers"
# Core only: the planning layer is not needed for the core tests (its
# concurrency test has its own ThreadSanitizer build below).
CC=clang CXX=clang++ cmake -G Ninja -S . -B build/clang-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$san_flags" \
  -DMDDUAL_SANITIZE=address,undefined \
  -DMDDUAL_BUILD_BENCHMARKS=OFF -DMDDUAL_BUILD_CLI=OFF -DMDDUAL_BUILD_PLANNING=OFF -DMDDUAL_BUILD_PYTHON=OFF \
  -DMDDUAL_WARNINGS_AS_ERRORS=ON
cmake --build build/clang-asan -j "$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/clang-asan -L core --output-on-failure -j "$jobs"

phase "the OMPL layer's concurrency test under ThreadSanitizer"
CC=clang CXX=clang++ cmake -G Ninja -S . -B build/clang-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$san_flags" \
  -DMDDUAL_SANITIZE=thread \
  -DMDDUAL_BUILD_BENCHMARKS=OFF -DMDDUAL_BUILD_CLI=OFF -DMDDUAL_WARNINGS_AS_ERRORS=ON
cmake --build build/clang-tsan -j "$jobs" --target test_planning_threads
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 ctest --test-dir build/clang-tsan -L tsan --output-on-failure

phase "fuzzing: libFuzzer targets under address + undefined sanitizers (scripts/fuzz.sh)"
./scripts/fuzz.sh

phase "format"
./scripts/check-format.sh
phase ""
echo "== all tests passed in $SECONDS s"
