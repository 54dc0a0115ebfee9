#!/usr/bin/env bash
# One arm motion check and one state check, mdd's certified check against
# OMPL's DiscreteMotionValidator with FCL at its default resolution (fcl) and
# with segments of at most 1/32 rad (fcl-fine), on the same link pairs, per problem set of configs/ROBOT (mddual_bench_arm_edges:
# edges drawn as RRT-Connect draws them, the fastest of the passes counts).
# Builds the benchmark (Release, build/release) and writes
# docs/results/arm-edges.md (arm7) or docs/results/<page>-edges.md with this
# command and the build.
#
#   scripts/run-arm-edges-bench.sh [SET ...]
#
# MDDUAL_ARM_ROBOT (default arm7; or panda) the robot, MDDUAL_ARM_PAGE
# (default the robot) the page, docs/results/<page>-edges.md (panda-mbm for
# the Panda's mbm_* sets),
# MDDUAL_ARM_PROBLEMS (default 2) problems per set, MDDUAL_ARM_EDGES (default
# 150) edges per problem, MDDUAL_ARM_PASSES (default 3) timed passes;
# MDDUAL_JOBS the build's parallelism.
set -euo pipefail
cd "$(dirname "$0")/.."
sets=("$@")
[ ${#sets[@]} -eq 0 ] && sets=(bookshelf_thin cage box table_pick table_under_pick table_bars)
problems="${MDDUAL_ARM_PROBLEMS:-2}"
edges="${MDDUAL_ARM_EDGES:-150}"
passes="${MDDUAL_ARM_PASSES:-3}"
jobs="${MDDUAL_JOBS:-$(nproc)}"
robot="${MDDUAL_ARM_ROBOT:-arm7}"
[ -d "configs/$robot/problems" ] || { echo "run-arm-edges-bench: no configs/$robot/problems" >&2; exit 2; }
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$jobs" --target mddual_bench_arm_edges >/dev/null
page="${MDDUAL_ARM_PAGE:-$robot}"
if [ "$page" != "$robot" ] && [ $# -eq 0 ]; then
  echo "run-arm-edges-bench: MDDUAL_ARM_PAGE=$page needs the sets to run (e.g. mbm_box)" >&2
  exit 2
fi
out=docs/results/arm-edges.md
robot_env=""
[ "$page" = arm7 ] || out="docs/results/$page-edges.md"
[ "$page" = "$robot" ] || robot_env="MDDUAL_ARM_PAGE=$page "
[ "$robot" = arm7 ] || robot_env="MDDUAL_ARM_ROBOT=$robot $robot_env"
command="${robot_env}MDDUAL_ARM_PROBLEMS=$problems MDDUAL_ARM_EDGES=$edges MDDUAL_ARM_PASSES=$passes ./scripts/run-arm-edges-bench.sh ${*}"
{
  echo "# $robot: one certified motion check against FCL's discrete ones"
  echo
  echo "Made by \`${command% }\` at $(git rev-parse --short HEAD) on $(date -u +%Y-%m-%d)," \
    "$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'))."
  echo "Per set, the first $problems problems, $edges edges each drawn as RRT-Connect draws them"
  echo "(from a valid state toward a uniform sample, at most 0.2 of the space's extent), checked by"
  echo "mdd (certified) and by OMPL's DiscreteMotionValidator with FCL at the default resolution (fcl)"
  echo "and with segments of at most 1/32 rad (fcl-fine, VAMP's resolution), on the same link pairs;"
  echo "thread CPU time, the fastest of $passes passes. \"mdd only\": edges fcl calls valid and mdd refuses"
  echo "(a contact between FCL's samples, or a false alarm); \"fcl only\": edges mdd calls valid and fcl"
  echo "or fcl-fine refuses (must be 0). Ratios above 1: mdd is faster."
  echo
  echo "| set | edges | colliding | mdd only | fcl only | mdd queries | fcl states | mdd us/edge | fcl us/edge | fcl/mdd | fcl-fine us/edge | fine/mdd | mdd us/state | fcl us/state | fcl/mdd |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} > "$out"
for s in "${sets[@]}"; do
  ./build/release/benchmarks/planning/mddual_bench_arm_edges "configs/$robot/problems/$s" \
    --robot "configs/$robot/$robot.urdf" --srdf "configs/$robot/$robot.srdf" --problems "$problems" --edges "$edges" \
    --passes "$passes" | grep '^| all ' | sed "s/^| all /| $s /" >> "$out"
done
echo "run-arm-edges-bench: $out"
