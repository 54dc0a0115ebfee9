#!/usr/bin/env bash
# Builds mddual (Release) and runs the main job on its built-in default.
# For now the main job is the CLI demo: generated polytopes, MDD-DUAL answers
# and the brute-force check of each.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
jobs="${MDDUAL_JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j "$jobs" --target mddual
./build/release/cli/mddual demo "$@"
