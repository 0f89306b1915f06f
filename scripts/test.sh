#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds the optimised and the sanitizer configurations, runs
# every test in Release and all but the long studies under the sanitizers, then short libFuzzer runs of the
# parsers (clang). CI (.ci/run) calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release
ctest --preset release
./scripts/build.sh debug-asan
ctest --preset debug-asan -E "$(grep -v '^#' tests/release_only.txt | paste -sd '|')"
CXX=clang++-14 cmake -S fuzz -B build/fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build/fuzz -j2
ctest --test-dir build/fuzz --output-on-failure -j2
