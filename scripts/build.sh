#!/usr/bin/env bash
# Configures and builds one preset (default: release) after making sure the dependencies are installed; further
# arguments name the targets to build (default: all).
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
shift $(( $# > 0 ? 1 : 0 ))
targets=()
for t in "$@"; do targets+=(--target "$t"); done
./scripts/install-deps.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)" "${targets[@]}"
