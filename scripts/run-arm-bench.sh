#!/usr/bin/env bash
# arm7's MotionBenchMaker problem sets (configs/arm7/problems) with `mddual
# bench`: the certified arm checker (mdd) against FCL with OMPL's discrete
# validator at its default resolution (fcl) and at 1/32 rad (fcl-fine),
# RRT-Connect and BKPIECE, the same runs, limits and seed for all three;
# every solution verified. Builds mddual (Release, build/release), writes
# out/bench-arms/<set>/ (logs, bench.db, plots, summary.md) and
# docs/results/arms.md (every set's summary table, with this command and the
# build).
#
#   scripts/run-arm-bench.sh [SET ...]
#
# MDDUAL_ARM_PROBLEMS (default 20) problems per set, MDDUAL_ARM_RUNS (default
# 3) runs per problem, planner and checker, MDDUAL_ARM_LIMIT (default 10)
# seconds per run. MDDUAL_ARM_BENCH_OUT changes out/bench-arms; MDDUAL_JOBS
# the build's parallelism.
set -euo pipefail
cd "$(dirname "$0")/.."
sets=("$@")
[ ${#sets[@]} -eq 0 ] && sets=(bookshelf_thin cage box table_pick table_under_pick table_bars)
problems="${MDDUAL_ARM_PROBLEMS:-20}"
runs="${MDDUAL_ARM_RUNS:-3}"
limit="${MDDUAL_ARM_LIMIT:-10}"
out="${MDDUAL_ARM_BENCH_OUT:-out/bench-arms}"
jobs="${MDDUAL_JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$jobs" --target mddual >/dev/null
mkdir -p "$out"
table="$out/arms.md"
command="MDDUAL_ARM_PROBLEMS=$problems MDDUAL_ARM_RUNS=$runs MDDUAL_ARM_LIMIT=$limit ./scripts/run-arm-bench.sh ${*}"
{
  echo "# arm7 on its MotionBenchMaker problem sets"
  echo
  echo "Made by \`${command% }\` at $(git rev-parse --short HEAD) on $(date -u +%Y-%m-%d)," \
    "$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')); seed 1."
  echo "Checkers: mdd (certified arm edges), fcl (FCL states, OMPL's discrete validator at its default"
  echo "resolution), fcl-fine (the same at 1/32 rad). A run without a verified solution counts at the limit."
  echo
} > "$table"
for s in "${sets[@]}"; do
  if [ ! -d "configs/arm7/problems/$s" ]; then
    echo "run-arm-bench: no problem set configs/arm7/problems/$s" >&2
    exit 2
  fi
  ./build/release/cli/mddual bench "configs/arm7/problems/$s" --robot configs/arm7/arm7.urdf \
    --srdf configs/arm7/arm7.srdf --planners RRTConnectkConfigDefault,BKPIECEGood --problems "$problems" \
    --runs "$runs" --time-limit "$limit" --seed 1 --output "$out/$s"
  cat "$out/$s/summary.md" >> "$table"
  echo >> "$table"
done
cp "$table" docs/results/arms.md
echo "run-arm-bench: docs/results/arms.md"
