#!/usr/bin/env bash
# The README's test command: set up (with the test packages), build every
# part (tests, benchmarks, Python package), and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests
scripts/build.sh --all
cd build
ctest --output-on-failure -j "$(nproc)"
