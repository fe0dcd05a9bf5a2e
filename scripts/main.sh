#!/usr/bin/env bash
# The README's main command: set up, build, and run the main job.
# Until `gyrotherm reproduce` exists (issue 5) the main job simulates the
# paper's −40..60 °C cycle with the built-in defaults.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
build/app/gyrotherm simulate scenarios/cycle.toml -o results/cycle.csv --plot results/cycle.png
