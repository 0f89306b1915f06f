#!/usr/bin/env bash
# The main job on the built-in example: installs what is missing, builds, and runs `trivar demo`.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release
./build/release/trivar demo --out out/demo "$@"
