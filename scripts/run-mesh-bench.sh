#!/usr/bin/env bash
# The mesh configs (bugtrap, twistycool, cubicles_mesh, apartment,
# maze_planar) with `mddual bench`: the MDD checker against FCL with OMPL's
# discrete validator, RRT-Connect, RRT, KPIECE and our mdd_rrtconnect, the same runs, limits and
# seed for both; every solution verified. Builds mddual (Release,
# build/release), writes out/bench-mesh/<config>/ (logs, bench.db, plots) and,
# without --no-readme, the mesh-results table of docs/results/mesh.md
# (scripts/mesh_results.py).
#
#   scripts/run-mesh-bench.sh [--no-readme] [CONFIG ...]
#
# MDDUAL_MESH_RUNS (default 5) runs per planner and checker, MDDUAL_MESH_LIMIT
# (default 10) seconds per run: at the defaults, at most 5 x 4 x 2 x 5 x 10 s =
# 33 minutes of planning plus the verification of the solutions.
# MDDUAL_MESH_BENCH_OUT changes out/bench-mesh; MDDUAL_JOBS the build's parallelism.
set -euo pipefail
cd "$(dirname "$0")/.."
readme=1
if [ "${1:-}" = "--no-readme" ]; then
  readme=0
  shift
fi
configs=("$@")
[ ${#configs[@]} -eq 0 ] && configs=(bugtrap twistycool cubicles_mesh apartment maze_planar)
runs="${MDDUAL_MESH_RUNS:-5}"
limit="${MDDUAL_MESH_LIMIT:-10}"
out="${MDDUAL_MESH_BENCH_OUT:-out/bench-mesh}"
jobs="${MDDUAL_JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$jobs" --target mddual >/dev/null
for c in "${configs[@]}"; do
  if [ ! -f "configs/$c/$c.cfg" ]; then
    echo "run-mesh-bench: no config configs/$c/$c.cfg" >&2
    exit 2
  fi
  ./build/release/cli/mddual bench "configs/$c/$c.cfg" --checkers mdd,fcl --planners rrtconnect,rrt,kpiece,mdd_rrtconnect \
    --runs "$runs" --time-limit "$limit" --seed 1 --output "$out/$c"
done
if [ "$readme" = 1 ]; then
  python3 scripts/mesh_results.py --bench "$out" --readme docs/results/mesh.md \
    --command "MDDUAL_MESH_RUNS=$runs MDDUAL_MESH_LIMIT=$limit ./scripts/run-mesh-bench.sh"
fi
