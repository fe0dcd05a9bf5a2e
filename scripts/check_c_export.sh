#!/usr/bin/env bash
# The one-line check that `gyrotherm export --format c` matches
# `gyrotherm compensate --causal`:
#
#   scripts/check_c_export.sh FIT.json DATA.csv
#
# exports FIT.json as a C header, compiles it (cc -std=c99 -Wall -Wextra
# -Werror -pedantic) with a small driver, runs it over DATA.csv, and compares
# its bias with compensate --causal's model_dph sample by sample (the CSV
# carries 9 decimals, so agreement shows as a largest difference ≤ 5e-10 °/h).
# DATA.csv must use gyrotherm's own column names (time_s, temp_c, gyro_dph,
# optional temp2_c) in s, °C and °/h; the fit must have one channel.
set -euo pipefail
fit=$(realpath "$1")
data=$(realpath "$2")
cd "$(dirname "$0")/.."
gt="$PWD/build/app/gyrotherm"
[ -x "$gt" ] || scripts/build.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$gt" export "$fit" --format c -o "$work/gt_comp.h" > /dev/null
cat > "$work/check.c" <<'C'
#include <stdio.h>
#include "gt_comp.h"
int main(void) {
  double t, T, T2, g;
  gt_comp_state s;
  gt_comp_init(&s);
  while (scanf("%lf %lf %lf %lf", &t, &T, &T2, &g) == 4) printf("%.17g\n", gt_comp_update_gyro(&s, t, T, T2, g));
  return 0;
}
C
cc -std=c99 -Wall -Wextra -Werror -pedantic -O2 "$work/check.c" -o "$work/check" -lm
# time, temperature, far-side temperature (0 if absent), gyro, by column name.
awk -F, '/^#/ {next}
  !header { for (i = 1; i <= NF; ++i) col[$i] = i; header = 1;
            if (!col["time_s"] || !col["temp_c"] || !col["gyro_dph"]) { print "need time_s, temp_c, gyro_dph" > "/dev/stderr"; exit 2 }
            next }
  { print $col["time_s"], $col["temp_c"], (col["temp2_c"] ? $col["temp2_c"] : 0), $col["gyro_dph"] }' \
  "$data" | "$work/check" > "$work/c.txt"
"$gt" compensate "$data" --fit "$fit" --causal -o "$work/comp.csv" > /dev/null
grep -v '^#' "$work/comp.csv" | tail -n +2 | cut -d, -f4 | paste -d' ' - "$work/c.txt" |
  awk '{ d = $1 - $2; if (d < 0) d = -d; if (d > m) m = d; n++ }
       END { printf "%d samples: largest |C - compensate --causal| = %.3g °/h%s\n", n, m, m <= 1e-9 ? " (match)" : " (MISMATCH)";
             exit m <= 1e-9 ? 0 : 1 }'
