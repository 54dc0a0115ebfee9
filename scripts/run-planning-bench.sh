#!/usr/bin/env bash
# Planning-layer speed: per scene, time per state check and per
# motion check, MDD-DUAL against FCL (OMPL's discrete validator at the default
# resolution, and FCL's continuous collision), with pair queries per check.
# Builds Release in build-bench/ and writes out/bench-planning.md (about a
# minute on the 2-core development machine, plus the build) and, for the mesh
# configs (configs/{bugtrap,twistycool,cubicles_mesh,apartment,maze_planar}),
# out/bench-planning-mesh.md (fewer states and edges, thread CPU time, no FCL
# continuous validators: about 10 minutes) and out/bench-replay.md (the motion
# checks KPIECE, RRT-Connect and RRT make in 3 s of planning on each mesh
# config, recorded and replayed with each checker: mddual_bench_replay, about
# 5 minutes); without arguments it also rewrites the planning tables of
# docs/results/planning-speed.md (scripts/planning_table.py, scripts/replay_table.py). With
# arguments, they are passed to the example-scene run only and the mesh runs
# are skipped.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MDDUAL_BENCH_BUILD_DIR:-$root/build-bench}"
out="${MDDUAL_BENCH_OUT:-$root/out}"
mkdir -p "$out"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DMDDUAL_BUILD_BENCHMARKS=ON -DMDDUAL_BUILD_TESTS=OFF \
  -DMDDUAL_BUILD_CLI=OFF -DMDDUAL_BUILD_PLANNING=ON >/dev/null
cmake --build "$build" -j2 --target mddual_bench_planning mddual_bench_replay
"$build/benchmarks/planning/mddual_bench_planning" "$@" | tee "$out/bench-planning.md"
# The tables of docs/results/planning-speed.md, from a run with the default sizes only.
if [ $# -eq 0 ]; then
  # The build the tables come from, named in their "Made by" lines.
  build_of="build of $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- ':!*.md' || echo ' with local changes'), $(date +%F)"
  python3 "$root/scripts/planning_table.py" --input "$out/bench-planning.md" --readme "$root/docs/results/planning-speed.md" \
    --command "./scripts/run-planning-bench.sh ($build_of)"
  mesh_args=(--states 2000 --edges 200 --passes 1 --cpu --no-ccd)
  configs=()
  for c in bugtrap twistycool cubicles_mesh apartment maze_planar; do configs+=(--config "$root/configs/$c/$c.cfg"); done
  "$build/benchmarks/planning/mddual_bench_planning" "${mesh_args[@]}" "${configs[@]}" | tee "$out/bench-planning-mesh.md"
  python3 "$root/scripts/planning_table.py" --input "$out/bench-planning-mesh.md" --readme "$root/docs/results/planning-speed.md" \
    --marker planning-mesh --command "./scripts/run-planning-bench.sh (mesh configs: mddual_bench_planning ${mesh_args[*]} --config ...; $build_of)"
  replay_args=(--planner kpiece --planner rrtconnect --planner rrt --seconds 3 --passes 2 --cpu)
  "$build/benchmarks/planning/mddual_bench_replay" "${replay_args[@]}" "${configs[@]}" | tee "$out/bench-replay.md"
  python3 "$root/scripts/replay_table.py" --input "$out/bench-replay.md" --readme "$root/docs/results/planning-speed.md" \
    --command "./scripts/run-planning-bench.sh (replay: mddual_bench_replay ${replay_args[*]} --config ...; $build_of)"
fi
