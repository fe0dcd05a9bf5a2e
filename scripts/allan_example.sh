#!/usr/bin/env bash
# The README's Allan example, regenerated: the default gyro on the paper's
# temperature cycle, before and after compensation by the paper's model
# fitted to the same record. Writes results/allan_cycle.png and the report
# beside it, results/allan_cycle.txt (a few seconds).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
gt="$PWD/build/app/gyrotherm"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$gt" simulate scenarios/cycle.toml -o "$work/cycle.csv" > /dev/null
"$gt" fit "$work/cycle.csv" -o "$work/fit.json" > /dev/null
(cd "$work" && "$gt" allan cycle.csv --fit fit.json --plot "$OLDPWD/results/allan_cycle.png") \
  | sed "s|$PWD/||" > results/allan_cycle.txt
echo "wrote results/allan_cycle.png and results/allan_cycle.txt"
