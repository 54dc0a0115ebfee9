#!/usr/bin/env bash
# Builds mddual (Release) and runs the main job on its built-in default: the
# OMPL benchmark of configs/thin_walls/thin_walls.cfg with MDD-DUAL's checker
# (mdd), FCL with OMPL's discrete motion validator (fcl) and FCL's continuous
# collision (fcl-continuous), every solution verified, with the config's own
# budgets (20 runs of at most 2 s per planner and checker: about half a
# minute on a 2-core machine once built, three at most). Writes
# out/bench/thin_walls/ (logs, bench.db, plots/, summary.md) and prints the
# summary table at the end.
#
# Extra arguments go to `mddual bench`, e.g. ./scripts/run.sh --runs 50, or
# another config: ./scripts/run.sh configs/maze_se2/maze_se2.cfg.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
jobs="${MDDUAL_JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j "$jobs" --target mddual
config=configs/thin_walls/thin_walls.cfg
if [ $# -gt 0 ] && [[ "$1" == *.cfg ]]; then
  config="$1"
  shift
fi
./build/release/cli/mddual bench "$config" "$@"
