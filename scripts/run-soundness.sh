#!/usr/bin/env bash
# The soundness suite: every case family of benchmarks/soundness/cases.h
# (translating-boxes, obb-hierarchy, rotating-link-arc, screw-vs-interpolated,
# thin-wall, far-from-origin, grazing, arm-rotating-link, sliver-mesh) with
# every checker (mdd, fcl, fcl-continuous, hull-cast, hull-cast-edge; the mesh
# families also fcl-continuous-obb and -rss; the arm family without
# fcl-continuous), against the families' ground truth. Builds
# Release in build-bench/ (MDDUAL_BENCH_BUILD_DIR), writes
# out/soundness/summary.md (MDDUAL_BENCH_OUT) and rewrites the table of
# docs/results/soundness.md (scripts/soundness_table.py). Arguments go to the
# runner (`--edges N` per family, default 200; `--seed S`); with any, the docs
# are left alone. About 10 s on the 2-core development machine, plus the build.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MDDUAL_BENCH_BUILD_DIR:-$root/build-bench}"
out="${MDDUAL_BENCH_OUT:-$root/out}/soundness"
mkdir -p "$out"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DMDDUAL_BUILD_BENCHMARKS=ON -DMDDUAL_BUILD_PLANNING=ON >/dev/null
cmake --build "$build" -j2 --target mddual_soundness
"$build/benchmarks/soundness/mddual_soundness" --out "$out/summary.md" "$@"
if [ $# -eq 0 ]; then
  # The build the table comes from, named in its "Made by" line.
  build_of="build of $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- ':!*.md' || echo ' with local changes'), $(date +%F)"
  python3 "$root/scripts/soundness_table.py" --input "$out/summary.md" \
    --command "./scripts/run-soundness.sh (seed 1, 200 edges per family; $build_of)"
fi
