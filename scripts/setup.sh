#!/usr/bin/env bash
# Installs the Debian 12 packages gyrotherm needs, only those that are
# missing; safe to run again. Needs root (or sudo).
#   scripts/setup.sh           the program's (scripts/main.sh: build it, run the main job)
#   scripts/setup.sh --tests   and those of the tests, benchmarks, Python package and
#                              fuzzing (scripts/test.sh, sanitize.sh, fuzz.sh; .ci/run)
# The program's list is the short one on purpose: a fresh machine gets about
# 160 packages for it (SUNDIALS alone brings OpenMPI, PETSc and Trilinos),
# against about 260 for both (docs/speed.md, "A first run").
set -euo pipefail

packages=(
  g++ cmake make ninja-build         # compiler and build (Ninja keeps both cores busy)
  gcc                                # C: SUNDIALS' CMake config looks for OpenMP_C
  libeigen3-dev                      # linear algebra
  libsundials-dev                    # CVODE (pulls in OpenMPI and PETSc)
  libcli11-dev                       # command line
  nlohmann-json3-dev                 # JSON
  libfmt-dev                         # formatting (g++ 12 has no <format>)
  libboost-dev                       # Boost.Math distributions, Boost.Random
  libtomlplusplus-dev                # TOML scenario files
  libpagmo-dev                       # peer optimisers (pso, de, cmaes, abc)
  libssl-dev                         # SHA-256 of input files (OpenSSL libcrypto)
  gnuplot-nox                        # plots
)
test_packages=(
  libgtest-dev libgmock-dev          # tests
  libbenchmark-dev                   # bench/
  clang libclang-rt-14-dev           # libFuzzer targets (scripts/fuzz.sh) and their sanitizer runtimes
  time                               # /usr/bin/time for peak memory (scripts/large_input.sh)
  python3-dev pybind11-dev           # the Python package (python/), for Debian's /usr/bin/python3
  python3-numpy python3-pandas       # its arrays and DataFrames
  python3-pytest python3-matplotlib  # its tests and plotting helpers
  jupyter-nbconvert python3-ipykernel  # the example notebook, executed by the tests
  chromium-headless-shell            # the report page loaded, shot and printed in a real browser
)
case "${1:-}" in
  "") ;;
  --tests) packages+=("${test_packages[@]}") ;;
  *) echo "usage: scripts/setup.sh [--tests]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "setup: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
