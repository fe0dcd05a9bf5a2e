#!/usr/bin/env bash
# Regenerates results/ols_coverage.md: coverage of ols's 95 % intervals over
# 100 seeds of the simulated cycle (about a minute).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/bench/ols_coverage results/ols_coverage.md 100
