#!/usr/bin/env bash
# Penetration-depth benchmark: builds mddual_bench_pd (Release) in
# build-bench/, runs the paper-protocol pairs (overlapping placements), random
# hulls of 10 to 5000 vertices and the hard inputs (flat, thin, deep,
# touching): our exact, shallow and approximate (delta 0.1, 0.01) PD against
# FCL (collide with contact: libccd MPR and indep EPA; signed distance: libccd
# EPA), Bullet's GjkEpa2 and the brute force, 3 timing passes, and writes
#   out/bench-pd.json   the summary (mddual_bench_pd --json)
#   out/bench-pd.md     the Markdown tables (scripts/bench_pd_table.py)
#   out/bench-pd.txt    the human-readable table printed by the run
#   out/bench-pd.err    reference mismatches and failure examples (with the
#                       pairs, ready to paste into a test or `mddual pd`)
# Extra arguments go to mddual_bench_pd, e.g.
#   scripts/run-pd-bench.sh --quick
#   scripts/run-pd-bench.sh --sets random --sizes 100,1000
# Environment: MDDUAL_BENCH_BUILD_DIR (default build-bench), MDDUAL_BENCH_OUT
# (default out).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MDDUAL_BENCH_BUILD_DIR:-$root/build-bench}"
out="${MDDUAL_BENCH_OUT:-$root/out}"
mkdir -p "$out"

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DMDDUAL_BUILD_BENCHMARKS=ON \
  -DMDDUAL_BUILD_TESTS=OFF -DMDDUAL_BUILD_CLI=OFF -DMDDUAL_BUILD_PLANNING=OFF >/dev/null
cmake --build "$build" -j2 --target mddual_bench_pd

label="$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if [ -n "$(git -C "$root" status --porcelain --untracked-files=no -- lib 2>/dev/null)" ]; then
  label="$label+dirty-lib"
fi

start=$(date +%s)
"$build/benchmarks/mddual_bench_pd" --json "$out/bench-pd.json" --label "$label" "$@" \
  2>"$out/bench-pd.err" | tee "$out/bench-pd.txt"
python3 "$root/scripts/bench_pd_table.py" "$out/bench-pd.json" >"$out/bench-pd.md"
echo "run-pd-bench: $(( $(date +%s) - start )) s; wrote $out/bench-pd.json, $out/bench-pd.md" \
  "($(grep -c '^MISMATCH' "$out/bench-pd.err" || true) reference mismatches in $out/bench-pd.err)"
