#!/usr/bin/env bash
# The README's report example, regenerated: the default gyro on the paper's
# temperature cycle with a hidden gradient effect, the paper's model fitted to
# it, and a cubic's PX4 export checked on the same record as PX4 applies it.
# Writes results/report.html and its JSON twin results/report.json.
set -euo pipefail
cd "$(dirname "$0")/.." && scripts/build.sh
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
cd "$work"
gt="$OLDPWD/build/app/gyrotherm" results="$OLDPWD/results"
"$gt" simulate "$OLDPWD/scenarios/cycle.toml" --hidden grad=0.02 -o cycle.csv > /dev/null
"$gt" fit cycle.csv --model "T + T^2 + T^3" -o poly.json > /dev/null
"$gt" export poly.json --format px4 -o gyro_tc.params 2> /dev/null
# The page names its log and fit as given; the date and SHA-256 are the run's.
"$gt" report cycle.csv --model "T + T^2 + dT" --params gyro_tc.params -o report.html 2> /dev/null
cp report.html report.json "$results/"
echo "wrote results/report.html and results/report.json"
