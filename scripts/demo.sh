#!/usr/bin/env bash
# The main job on the built-in example: installs what is missing, builds the trivar program and the Python
# module (not the tests and benchmarks), and runs `trivar demo`.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release trivar_cli trivar_python
./build/release/trivar demo --out out/demo "$@"
