#!/usr/bin/env bash
# Regenerates results/ols_coverage.md: coverage of ols's 95 % intervals over
# 200 seeds of the simulated cycle for each noise (white, white + flicker,
# flicker, white + Gauss–Markov 1000 s and 1 h, white + random walk), with the
# identified-noise intervals and the Newey–West ones (about 6 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/bench/ols_coverage results/ols_coverage.md 200
