#!/usr/bin/env bash
# The README's main command: set up, build, and run the main job,
# `gyrotherm reproduce` on the built-in defaults (the paper's Table 1 on the
# simulated gyro), writing results/table1.md, table1.json and the figures.
# Only the program's packages and the program itself (scripts/test.sh adds
# the rest): a few minutes on a fresh 2-core machine (docs/speed.md).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh gyrotherm
build/app/gyrotherm reproduce --out results
