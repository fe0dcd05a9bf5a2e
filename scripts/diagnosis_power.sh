#!/usr/bin/env bash
# Regenerates results/diagnosis_power.md (the cycle: false alarms, steps and
# registry effects under four kinds of noise, SEEDS per row) and
# results/diagnosis_power_random.md (false alarms on the 75 h random profile).
# About 50 minutes on 2 cores at 100 seeds: the cycle's four noise cells run
# as two halves side by side, joined after.
set -euo pipefail
cd "$(dirname "$0")/.."
seeds="${1:-100}" && scripts/build.sh
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
build/bench/diagnosis_power "$work/a.md" "$seeds" all cycle 0,1 &
build/bench/diagnosis_power "$work/b.md" "$seeds" all cycle 2,3 &
build/bench/diagnosis_power results/diagnosis_power_random.md "$seeds" clean random &
wait
# One file: a's header and cells, then b's cells (its text after the header).
{ sed "s|$work/a.md|results/diagnosis_power.md|; s|\`, \([0-9]*\) min)|\` on cells 0,1 and 2,3 side by side, \1 min)|" "$work/a.md"
  sed -n '/^## /,$p' "$work/b.md"; } > results/diagnosis_power.md
echo "wrote results/diagnosis_power.md and results/diagnosis_power_random.md"
