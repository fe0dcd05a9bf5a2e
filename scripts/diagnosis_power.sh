#!/usr/bin/env bash
# Regenerates results/diagnosis_power.md (the cycle: false alarms, steps and
# registry effects under four kinds of noise, SEEDS per row) and
# results/diagnosis_power_random.md (false alarms on the 75 h random profile).
# About 45 minutes on 2 cores at 100 seeds; both runs go side by side.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
seeds="${1:-100}"
build/bench/diagnosis_power results/diagnosis_power.md "$seeds" all cycle &
build/bench/diagnosis_power results/diagnosis_power_random.md "$seeds" clean random &
wait
