#!/usr/bin/env bash
# Core speed/accuracy benchmark, full MDD-DUAL paper protocol (docs/algorithms.md
# section 5): builds mddual_bench_core (Release) in build-bench/, runs the ten
# pairs with 40 orientations x 21 placements x 40 directions = 33,600 queries
# per pair (ours cold/warm mdd and toi, Bullet and FCL casts, 3 timing passes),
# and writes
#   out/bench-core.json   the summary (mddual_bench_core --json)
#   out/bench-core.md     the tables of docs/results/core.md (scripts/bench_core_table.py)
#   out/bench-core.txt    the human-readable table printed by the run
#   out/bench-core.err    self-check messages and failure examples (with the
#                         queries, ready to paste into a test)
# Run time on the 2-core development machine (AMD EPYC VM, shared with other
# builds): about 3 minutes for the full protocol (167 s measured at c95dbce;
# a third of it builds the scenes and brute-force references), plus the build;
# with --quick about 40 s.
# Extra arguments go to mddual_bench_core, e.g.
#   scripts/run-core-bench.sh --quick
#   scripts/run-core-bench.sh --pair P4-P6 --directions 10
# Environment: MDDUAL_BENCH_BUILD_DIR (default build-bench), MDDUAL_BENCH_OUT
# (default out).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MDDUAL_BENCH_BUILD_DIR:-$root/build-bench}"
out="${MDDUAL_BENCH_OUT:-$root/out}"
mkdir -p "$out"

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DMDDUAL_BUILD_BENCHMARKS=ON \
  -DMDDUAL_BUILD_TESTS=OFF -DMDDUAL_BUILD_CLI=OFF -DMDDUAL_BUILD_PLANNING=OFF >/dev/null
cmake --build "$build" -j2 --target mddual_bench_core

label="$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if [ -n "$(git -C "$root" status --porcelain --untracked-files=no -- lib 2>/dev/null)" ]; then
  label="$label+dirty-lib"
fi

start=$(date +%s)
"$build/benchmarks/mddual_bench_core" --json "$out/bench-core.json" --label "$label" "$@" \
  2>"$out/bench-core.err" | tee "$out/bench-core.txt"
python3 "$root/scripts/bench_core_table.py" "$out/bench-core.json" >"$out/bench-core.md"
echo "run-core-bench: $(( $(date +%s) - start )) s; wrote $out/bench-core.json, $out/bench-core.md" \
  "($(grep -c '^CHECK' "$out/bench-core.err" || true) self-check messages in $out/bench-core.err)"
