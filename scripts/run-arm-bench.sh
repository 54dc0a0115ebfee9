#!/usr/bin/env bash
# An arm's MotionBenchMaker problem sets (configs/<robot>/problems) with `mddual
# bench`: the certified arm checker (mdd) against FCL with OMPL's discrete
# validator at its default resolution (fcl) and at 1/32 rad (fcl-fine),
# and the Bullet hull cast (hull-cast) when built with Bullet, RRT-Connect
# and BKPIECE, the same runs, limits and seed for all;
# every solution verified. Builds mddual (Release, build/release), writes
# out/bench-arms/<set>/ (logs, bench.db, plots, summary.md) and
# docs/results/arms.md (every set's summary table, with this command and the
# build), then the README's arm table from every robot's page
# (scripts/arm_headline.py).
#
#   scripts/run-arm-bench.sh [SET ...]
#   MDDUAL_ARM_ROBOT=panda scripts/run-arm-bench.sh [SET ...]
#
# MDDUAL_ARM_ROBOT (default arm7) picks the robot: configs/<robot>/<robot>.urdf
# and .srdf and its sets; for a robot other than arm7 the outputs are
# out/bench-arms-<robot>/ and docs/results/<robot>.md. MDDUAL_ARM_PAGE names
# another page for other sets of the same robot (the sets must then be named;
# scripts/arm_headline.py reads arms.md, panda.md and panda-mbm.md), e.g. the
# Panda's sets in MotionBenchMaker's own scenes:
#   MDDUAL_ARM_ROBOT=panda MDDUAL_ARM_PAGE=panda-mbm scripts/run-arm-bench.sh \
#     mbm_bookshelf_thin mbm_box mbm_table_pick mbm_table_under_pick
# MDDUAL_ARM_PROBLEMS (default 20) problems per set, MDDUAL_ARM_RUNS (default
# 3) runs per problem, planner and checker, MDDUAL_ARM_LIMIT (default 10)
# seconds per run. MDDUAL_ARM_BENCH_OUT changes out/bench-arms; MDDUAL_JOBS
# the build's parallelism.
set -euo pipefail
cd "$(dirname "$0")/.."
sets=("$@")
[ ${#sets[@]} -eq 0 ] && sets=(bookshelf_thin cage box table_pick table_under_pick table_bars)
robot="${MDDUAL_ARM_ROBOT:-arm7}"
config="configs/$robot"
if [ ! -f "$config/$robot.urdf" ] || [ ! -f "$config/$robot.srdf" ]; then
  echo "run-arm-bench: no robot $config/$robot.urdf and $config/$robot.srdf" >&2
  exit 2
fi
page="${MDDUAL_ARM_PAGE:-$robot}"
if [ "$page" != "$robot" ] && [ $# -eq 0 ]; then
  echo "run-arm-bench: MDDUAL_ARM_PAGE=$page needs the sets to run (e.g. mbm_box)" >&2
  exit 2
fi
if [ "$page" = arm7 ] && [ "$robot" != arm7 ]; then
  echo "run-arm-bench: MDDUAL_ARM_PAGE=arm7 is arm7's page (docs/results/arms.md)" >&2
  exit 2
fi
if [ "$page" = arm7 ]; then
  results=docs/results/arms.md
  default_out=out/bench-arms
else
  results="docs/results/$page.md"
  default_out="out/bench-arms-$page"
fi
problems="${MDDUAL_ARM_PROBLEMS:-20}"
runs="${MDDUAL_ARM_RUNS:-3}"
limit="${MDDUAL_ARM_LIMIT:-10}"
out="${MDDUAL_ARM_BENCH_OUT:-$default_out}"
jobs="${MDDUAL_JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$jobs" --target mddual >/dev/null
mkdir -p "$out"
table="$out/$(basename "$results")"
command="MDDUAL_ARM_PROBLEMS=$problems MDDUAL_ARM_RUNS=$runs MDDUAL_ARM_LIMIT=$limit ./scripts/run-arm-bench.sh ${*}"
[ "$page" = "$robot" ] || command="MDDUAL_ARM_PAGE=$page $command"
[ "$robot" = arm7 ] || command="MDDUAL_ARM_ROBOT=$robot $command"
{
  echo "# $robot on its MotionBenchMaker problem sets"
  echo
  echo "Made by \`${command% }\` at $(git rev-parse --short HEAD) on $(date -u +%Y-%m-%d)," \
    "$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')); seed 1."
  echo "Checkers: mdd (certified arm edges), fcl (FCL states, OMPL's discrete validator at its default"
  echo "resolution), fcl-fine (the same at 1/32 rad), and hull-cast (FCL states, Bullet casts of each link"
  echo "piece's hull between states at OMPL's resolution) when built with Bullet. A run without a verified"
  echo "solution counts at the limit. \"median solve\" is the planner's own solve() time: OMPL's \"time\" also"
  echo "holds up to 1 ms of its benchmark's termination-condition thread, the same for every checker."
  echo
} > "$table"
for s in "${sets[@]}"; do
  if [ ! -d "$config/problems/$s" ]; then
    echo "run-arm-bench: no problem set $config/problems/$s" >&2
    exit 2
  fi
  ./build/release/cli/mddual bench "$config/problems/$s" --robot "$config/$robot.urdf" \
    --srdf "$config/$robot.srdf" --planners RRTConnectkConfigDefault,BKPIECEGood --problems "$problems" \
    --runs "$runs" --time-limit "$limit" --seed 1 --output "$out/$s"
  cat "$out/$s/summary.md" >> "$table"
  echo >> "$table"
done
cp "$table" "$results"
echo "run-arm-bench: $results"
# The README's arm table: the RRT-Connect rows of every robot's page.
python3 scripts/arm_headline.py
echo "run-arm-bench: README.md (arm table)"
