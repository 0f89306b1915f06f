#!/usr/bin/env bash
# Installs trivar's build and test dependencies from Debian packages.
# Idempotent: packages already present are skipped, so a warm machine does no apt work.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache
  libeigen3-dev libcli11-dev nlohmann-json3-dev libpng-dev zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3  # tests read output files back with its standard library (xml, zlib, struct, zipfile)
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module `trivar` (python/) and its tests
  libsuitesparse-dev libspectra-dev libgmp-dev
  libxml2-dev  # G+Smo XML files
  clang-14 libclang-rt-14-dev libomp-14-dev
  petsc-dev slepc-dev libopenmpi-dev openmpi-bin  # distributed assembly and solvers (iga_petsc/), mpiexec for its tests
  libosd-dev  # OpenSubdiv: test reference for Catmull-Clark limit surfaces (tests/tspline)
  valgrind  # bench/check counts the instructions of the hot kernels with callgrind
  # OpenCASCADE: STEP B-rep import, exact NURBS conversion, trimmed-face tessellation, test solids
  libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "trivar: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
