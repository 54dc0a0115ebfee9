#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with Clang under ASan + UBSan and runs
# each one for a fixed number of executions from the seed corpus:
#   fuzz_polytope  seeds in fuzz/seeds/polytope
#   fuzz_cfg       configs/**/*.cfg
#   fuzz_urdf      configs/**/*.urdf
#   fuzz_mesh      configs/**/meshes/* (first byte: the format)
#   fuzz_jsonl     fuzz/seeds/jsonl (first byte: pd's method)
#   fuzz_mbm       configs/arm7's first problems, witness paths and SRDF (first byte: the reader)
# plus every past finding in fuzz/findings (named <target>-<what>).
# MDDUAL_FUZZ_RUNS sets the executions of every target (default: per target,
# below, about 25 to 60 s each on a 2-core machine); -seed=1 makes a run
# repeatable. The targets run side by side (MDDUAL_JOBS at a time, default
# all cores); a crash, a sanitizer report or a wrong answer in one fails the
# script once all have finished, with the input saved as build/clang-fuzz/crash-*
# (turn it into a regression test).
set -euo pipefail
cd "$(dirname "$0")/.."
# Executions per target (about 25 to 60 s each here): the mesh loader runs
# at ~35 executions/s, the others at 150 to 400.
declare -A default_runs=([polytope]=10000 [cfg]=10000 [urdf]=10000 [mesh]=2000 [jsonl]=8000 [mbm]=20000)
jobs="${MDDUAL_JOBS:-$(nproc)}"
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz.sh: MDDUAL_JOBS must be a positive integer (got '$jobs')"; exit 1; }
declare -A pids
for tool in clang++ ninja; do
  command -v "$tool" >/dev/null || { echo "fuzz.sh: $tool not found (./scripts/install-deps.sh installs it)"; exit 1; }
done
# -O1 and line tables only, as the sanitizer builds of scripts/test.sh.
source scripts/instrumented-flags.sh
# Ninja, not Make: it compiles a target's files while the libraries it links
# are still being built (149 s -> 107 s for this build on the 2-core machine).
fuzz_dir=build/clang-fuzz
CC=clang CXX=clang++ cmake -G Ninja -S . -B "$fuzz_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$instrumented_flags" -DMDDUAL_BUILD_FUZZERS=ON \
  -DMDDUAL_BUILD_TESTS=OFF -DMDDUAL_BUILD_BENCHMARKS=OFF -DMDDUAL_BUILD_CLI=OFF >/dev/null
cmake --build "$fuzz_dir" -j "$jobs" --target fuzz_polytope fuzz_cfg fuzz_urdf fuzz_mesh fuzz_jsonl fuzz_mbm

corpus="$fuzz_dir/corpus"
rm -rf "$corpus"
mkdir -p "$corpus"/{polytope,cfg,urdf,mesh,jsonl,mbm}
cp fuzz/seeds/polytope/* "$corpus/polytope/"
cp fuzz/seeds/jsonl/* "$corpus/jsonl/"
# Past findings replay first in every run (fuzz/findings/<target>-*).
for f in fuzz/findings/*; do
  [ -e "$f" ] || continue
  name=$(basename "$f")
  cp "$f" "$corpus/${name%%-*}/"
done
find configs -name '*.cfg' -exec cp {} "$corpus/cfg/" \;
find configs -name '*.urdf' -exec cp {} "$corpus/urdf/" \;
i=0
while IFS= read -r -d '' mesh; do
  # The mesh target reads the format from the first byte (0 obj, 1 stl, 2 dae, 3 ply).
  case "$mesh" in
    *.obj) b='\x00' ;; *.stl) b='\x01' ;; *.dae) b='\x02' ;; *.ply) b='\x03' ;; *) continue ;;
  esac
  { printf "$b"; head -c 65536 "$mesh"; } >"$corpus/mesh/seed$i"
  i=$((i + 1))
done < <(find configs -path '*meshes*' -type f -print0)

# The mbm target reads the reader from the first byte (0 scene, 1 request, 2 SRDF,
# 3 trajectory).
for set in configs/arm7/problems/*; do
  { printf '\x00'; cat "$set/scene0001.yaml"; } >"$corpus/mbm/$(basename "$set")-scene"
  { printf '\x01'; cat "$set/request0001.yaml"; } >"$corpus/mbm/$(basename "$set")-request"
  { printf '\x03'; cat "$set/trajectory0001.yaml"; } >"$corpus/mbm/$(basename "$set")-trajectory"
done
{ printf '\x02'; cat configs/arm7/arm7.srdf; } >"$corpus/mbm/arm7-srdf"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
# $jobs targets at a time (each libFuzzer run is single-threaded; one after
# another they took 115 s on the 2-core machine, mesh 42, polytope 30, jsonl
# 28, urdf 10, cfg 5; two at a time 58 s), longest first; the summaries are
# printed in this order, and any finding fails the script after all have run.
# (The background jobs share the script's process group: an interrupt from
# the terminal reaches the fuzzers too.)
run_target() {
  local target=$1 runs start
  runs="${MDDUAL_FUZZ_RUNS:-${default_runs[$target]}}"
  echo "== fuzz_$target: $runs executions"
  start=$(date +%s)
  (cd "$fuzz_dir" && ./fuzz/fuzz_$target -seed=1 -runs="$runs" -max_len=65536 -timeout=10 -rss_limit_mb=4096 \
    "corpus/$target" 2>"fuzz_$target.log") || {
    tail -40 "$fuzz_dir/fuzz_$target.log"
    echo "fuzz_$target found a problem (log: $fuzz_dir/fuzz_$target.log)"
    return 1
  }
  grep -E "^Done [0-9]+ runs" "$fuzz_dir/fuzz_$target.log" || true
  echo "fuzz_$target: $runs executions in $(($(date +%s) - start)) s, no finding"
}
targets=(mesh polytope jsonl mbm urdf cfg)
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  run_target "$target" >"$fuzz_dir/fuzz_$target.summary" 2>&1 &
  pids[$target]=$!
done
failed=0
for target in "${targets[@]}"; do
  wait "${pids[$target]}" || failed=1
  cat "$fuzz_dir/fuzz_$target.summary"
done
exit "$failed"
