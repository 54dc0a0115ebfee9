#!/usr/bin/env bash
# The full benchmark runs behind docs/results/: every config of configs/ with
# all three checkers (mdd, fcl, fcl-continuous) and the config's planners, with
# the run counts and time limits below (the same for every checker; chosen so
# that each config takes at most about 15 minutes on a 2-core machine, except
# the mesh configs of OMPL.app's sizes: bugtrap, twistycool, cubicles_mesh,
# apartment, maze_planar, where runs that time out can bring a config to 30
# minutes (3 checkers x 3 planners x runs x limit), plus the verification of
# the solutions found, which on the apartment's 40,000 triangles takes seconds
# per path). Builds
# mddual (Release, build/release), runs `mddual bench` per config into
# out/bench-full/<config>/, then writes docs/results/: one plot per config
# (<config>.png) and README.md with the machine, the commands, each config's
# wall time and its summary table; the results table of docs/results/overview.md
# and, when all five example configs ran, the README's headline table
# (scripts/results_overview.py, from every config's database under the output).
#
#   scripts/run-full-bench.sh                  all ten configs (hours: see above)
#   scripts/run-full-bench.sh thin_walls maze_se2   some of them (docs/results/README.md
#                                              then lists only those)
# MDDUAL_FULL_BENCH_OUT changes out/bench-full; MDDUAL_JOBS the build's parallelism.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
jobs="${MDDUAL_JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$jobs" --target mddual >/dev/null

out="${MDDUAL_FULL_BENCH_OUT:-out/bench-full}"
results=docs/results
seed=1
# config: runs per planner and checker, seconds per run.
# Mesh configs: their cfg's budgets, fewer and longer runs as the meshes grow
# (cubicles_mesh and maze_planar plan in about a second or less with FCL,
# bugtrap in seconds; twistycool's slot is narrow and the apartment large).
declare -A runs=([thin_walls]=100 [convex_field]=100 [narrow_passage]=20 [maze_se2]=100 [cubicles]=100
                 [bugtrap]=10 [twistycool]=10 [cubicles_mesh]=20 [apartment]=5 [maze_planar]=20)
declare -A limit=([thin_walls]=5 [convex_field]=10 [narrow_passage]=10 [maze_se2]=10 [cubicles]=10
                  [bugtrap]=15 [twistycool]=15 [cubicles_mesh]=10 [apartment]=30 [maze_planar]=10)
configs=("$@")
if [ ${#configs[@]} -eq 0 ]; then
  configs=(thin_walls convex_field narrow_passage maze_se2 cubicles bugtrap twistycool cubicles_mesh apartment
           maze_planar)
fi

mkdir -p "$results"
declare -A seconds
declare -A command
for c in "${configs[@]}"; do
  if [ -z "${runs[$c]:-}" ]; then
    echo "run-full-bench: unknown config '$c' (known: ${!runs[*]})" >&2
    exit 2
  fi
  cmd=(./build/release/cli/mddual bench "configs/$c/$c.cfg" --runs "${runs[$c]}" --time-limit "${limit[$c]}"
       --seed "$seed" --output "$out/$c")
  command[$c]="${cmd[*]}"
  echo "== ${command[$c]}" >&2
  start=$(date +%s)
  "${cmd[@]}"
  seconds[$c]=$(($(date +%s) - start))
  cp "$out/$c/plots/$c.png" "$results/$c.png"
done

cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
{
  echo "# Full benchmark runs"
  echo
  echo "Made by \`scripts/run-full-bench.sh\` at commit $(git rev-parse --short HEAD) on $(date -u +%Y-%m-%d)."
  echo "Machine: $(nproc) cores, $cpu, $(uname -sr); OMPL $(dpkg-query -W -f='${Version}' libompl-dev 2>/dev/null || echo '?'),"
  echo "FCL $(dpkg-query -W -f='${Version}' libfcl-dev 2>/dev/null || echo '?'). Seed $seed. Every checker gets the same runs and time limit."
  echo
  echo "Columns (scripts/bench_report.py): success = runs whose solution the strict verification found"
  echo "collision-free; median time over all runs, runs without a verified solution counted at the time limit;"
  echo "time / FCL = that median over the fcl checker's (FCL + OMPL's discrete motion validator at the default"
  echo "resolution); median solve, solve / FCL = the same over the planner's own solve() time (OMPL's time"
  echo "also holds up to 1 ms of its benchmark's termination-condition thread); solved time = median solve time"
  echo "of the runs that returned an exact solution, valid or not; checking = median share of the solve time"
  echo "spent in the checkers; invalid = solutions in collision;"
  echo "invalid raw = solutions whose path was already in collision before OMPL's simplification."
  for c in "${configs[@]}"; do
    echo
    echo "## $c"
    echo
    echo "\`${command[$c]}\` (${seconds[$c]} s)"
    echo
    cat "$out/$c/summary.md"
    echo
    echo "![$c]($c.png)"
  done
} >"$results/README.md"
# The overview of docs/results/overview.md and, from a run of all five example
# configs, the README's headline table (their RRT-Connect rows).
headline=()
missing=0
for c in thin_walls convex_field narrow_passage maze_se2 cubicles; do
  found=0
  for ran in "${configs[@]}"; do [ "$ran" = "$c" ] && found=1; done
  [ "$found" = 1 ] || missing=1
done
if [ "$missing" = 0 ]; then
  headline=(--headline README.md --made-by "./scripts/run-full-bench.sh ${configs[*]} at $(git rev-parse --short HEAD), \
$(date -u +%Y-%m-%d); $(nproc) cores, $cpu; seed $seed")
fi
python3 scripts/results_overview.py --bench "$out" --readme docs/results/overview.md "${headline[@]}"
echo "run-full-bench: wrote $results/README.md, the plots and docs/results/overview.md" >&2
if [ ${#headline[@]} -gt 0 ]; then echo "run-full-bench: and the headline table of README.md" >&2; fi
