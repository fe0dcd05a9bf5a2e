#!/usr/bin/env bash
# Regenerates results/diagnosis_false_alarms.md: how often diagnose calls
# anything significant (a term, a log column, a bias step) on clean simulated
# records, 100 seeds of the cycle, 10 of the random profile and 100 of the
# cycle with white + Gauss–Markov noise (about 40 minutes on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/bench/diagnosis_false_alarms results/diagnosis_false_alarms.md "${1:-100}" "${2:-10}" "${3:-100}"
