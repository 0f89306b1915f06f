#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds the optimised and the sanitizer configurations,
# and runs every test in both. CI (.ci/run) calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
for preset in release debug-asan; do
  ./scripts/build.sh "$preset"
  ctest --preset "$preset"
done
