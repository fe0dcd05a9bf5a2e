#!/usr/bin/env bash
# Regenerates results/ols_coverage.md: coverage of the 95 % intervals of ols
# (identified noise, bootstrap, Newey–West) and gls, some with --sensor-tau 20,
# over 200 seeds per noise (white, white + flicker, flicker, white +
# Gauss–Markov 1000 s and 1 h, white + random walk) of the simulated cycle, the
# short cycle and the 75 h random profile (about 30 minutes on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/bench/ols_coverage results/ols_coverage.md 200
