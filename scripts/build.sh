#!/usr/bin/env bash
# Configures and builds indentsim (Release, ccache) into ./build. Used by the two main scripts.
# Usage: bash scripts/build.sh [TARGET...]   (no target: everything, benchmarks included)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/install_dependencies.sh
jobs="${INDENTSIM_BUILD_JOBS:-$(nproc)}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
targets=()
[[ $# -gt 0 ]] && targets=(--target "$@")
cmake --build build -j "$jobs" "${targets[@]}" >> build.log 2>&1 || { tail -n 80 build.log; exit 1; }
echo "build: ok (log in build.log)"
