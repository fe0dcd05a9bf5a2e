#!/usr/bin/env bash
# The README's diagnosis examples beyond the registry, regenerated: a mode hop
# (+0.006 °/h at 5.5 h) and a bias that follows a logged supply voltage, each
# added by awk to a clean simulated cycle as a user's own record would carry
# them. Writes the figures to results/diagnose/ and the transcripts beside
# them (a few seconds).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
top="$PWD"
gt="$PWD/build/app/gyrotherm"
out="$PWD/results/diagnose"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
cd "$work"
"$gt" simulate "$OLDPWD/scenarios/cycle.toml" -o clean.csv > /dev/null
# A mode hop: the gyro column (6th) steps by +0.006 °/h at 19800 s.
awk -F, 'BEGIN{OFS=","} /^#/||/^time/{print;next} {if ($1>=19800) $6=sprintf("%.6f",$6+0.006); print}' \
  clean.csv > hop.csv
# A supply voltage that wanders apart from the temperature, logged as a
# column, and a bias of 0.01 °/h per volt that follows it.
awk -F, 'BEGIN{OFS=","; pi=3.14159265358979}
  /^#/{print;next} /^time/{print $0 ",supply_v";next}
  {v=28+0.3*sin(2*pi*$1/7200)+0.2*sin(2*pi*$1/20000+1); $6=sprintf("%.6f",$6+0.01*(v-28)); print $0 "," sprintf("%.4f",v)}' \
  clean.csv > volt.csv
run() {  # name, then diagnose's arguments
  local name=$1; shift
  rm -rf "$out/$name"
  # (paths as seen from the repository's top folder, so the transcripts hold no machine's path)
  "$gt" diagnose "$@" --plots "$out/$name" | sed "s|$top/||" > "$out/$name.txt"
}
run hop hop.csv
run hop_after hop.csv --model "T + T^2 + dT + step@20000"  # as its next: line says
run volt volt.csv
run volt_after volt.csv --model "T + T^2 + dT + supply_v"
echo "wrote $out"
