#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds the optimised and the sanitizer configurations,
# runs every test in both, then a short libFuzzer run of the STEP reader (clang). CI (.ci/run) calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
for preset in release debug-asan; do
  ./scripts/build.sh "$preset"
  ctest --preset "$preset"
done
CXX=clang++-14 cmake -S fuzz -B build/fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build/fuzz -j2
ctest --test-dir build/fuzz --output-on-failure
