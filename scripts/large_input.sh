#!/usr/bin/env bash
# Measures fitting a 10-day log at 10 Hz (8.76 million rows): simulates it
# once into build/large/ (about 580 MB), then, from the page cache, times
# `gyrotherm fit` on it five times beside `wc -l` and `cat` of the same file
# (interleaved, so that the ratios are of one moment on a shared machine),
# records the peak memory, and runs bench_io's large-log benchmarks (a plain
# read of the bytes, parsing alone, preparing alone, the preparing thread
# alone, fit) on it; writes results/large_input.md and
# results/bench_large.json and results/bench_large_commands.json (the
# commands' median seconds), which scripts/bench.sh includes in
# results/benchmarks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p build/large
scenario=build/large/tenday.toml
{
  echo "name = \"tenday\""
  echo "rig = \"$(pwd)/scenarios/rig_ins.toml\""
  echo "gyro = \"$(pwd)/scenarios/gyro.toml\""
  echo "seed = 10"
  echo "sample_rate_hz = 10.0"
  echo "start_c = 20.0"
  echo "initial = \"steady\""
  for day in 1 2 3 4 5 6 7 8 9 10; do
    for t in 40 0 20; do
      printf '[[segment]]\nkind = "ramp"\ntarget_c = %s\nrate_c_per_min = 1.0\n' "$t"
      printf '[[segment]]\nkind = "hold"\ntemp_c = %s\nduration_min = 460\n' "$t"
    done
  done
} > "$scenario"
if [ ! -f build/large/tenday.csv ]; then
  build/app/gyrotherm simulate "$scenario" -o build/large/tenday.csv
fi
rows=$(($(wc -l < build/large/tenday.csv) - 3))
size="$(($(stat -c %s build/large/tenday.csv) / 1000000)) MB ($(du -m build/large/tenday.csv | cut -f1) MiB)"
csv=build/large/tenday.csv
cat "$csv" > /dev/null  # into the page cache
/usr/bin/time -v build/app/gyrotherm fit "$csv" > build/large/fit.txt 2> build/large/time.txt
# seconds COMMAND...: the wall time of one run, output discarded.
seconds() {
  local start=$EPOCHREALTIME
  "$@" > /dev/null
  awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.4f\n", b - a }'
}
: > build/large/times.txt
for run in 1 2 3 4 5; do
  echo "cat $(seconds cat "$csv")" >> build/large/times.txt
  echo "wc $(seconds wc -l "$csv")" >> build/large/times.txt
  echo "fit $(seconds build/app/gyrotherm fit "$csv")" >> build/large/times.txt
done
# median NAME: of the five times.
median() { awk -v n="$1" '$1 == n { print $2 }' build/large/times.txt | sort -g | sed -n 3p; }
cat_s=$(median cat); wc_s=$(median wc); fit_s=$(median fit)
bytes=$(stat -c %s "$csv")
per_s() { awk -v b="$bytes" -v t="$1" 'BEGIN { printf "%.0f", b / t / 1e6 }'; }
printf '{\n  "file_bytes": %s,\n  "cat_s": %s,\n  "wc_l_s": %s,\n  "fit_s": %s\n}\n' \
  "$bytes" "$cat_s" "$wc_s" "$fit_s" > results/bench_large_commands.json
GYROTHERM_LARGE_CSV=build/large/tenday.csv build/bench/bench_io --benchmark_filter=LargeLog \
  --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out=results/bench_large.json.tmp --benchmark_out_format=json > /dev/null
mv results/bench_large.json.tmp results/bench_large.json
# field BENCHMARK FIELD: from the medians in results/bench_large.json.
field() {
  awk -v name="\"name\": \"$1/iterations:1/real_time_median\"," -v field="\"$2\":" '
    index($0, name) { inside = 1; next }
    inside && index($0, field) { sub(/^[^:]*: */, ""); sub(/,$/, ""); print; exit }
    inside && /^ *}/ { inside = 0 }' results/bench_large.json
}
mbs() { awk -v b="$(field "$1" bytes_per_second)" 'BEGIN { printf "%.0f", b / 1e6 }'; }
secs() { awk -v t="$(field "$1" real_time)" 'BEGIN { printf "%.2f", t / 1e3 }'; }
read_mbs=$(mbs BM_LargeLog_Read); parse_mbs=$(mbs BM_LargeLog_Parse); fit_mbs=$(mbs BM_LargeLog_Fit)
prepare_mbs=$(mbs BM_LargeLog_Prepare); filter_mbs=$(mbs BM_LargeLog_Filter)
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
rss_kb=$(awk -F: '/Maximum resident set size/ {gsub(/ /,"",$2); print $2}' build/large/time.txt)
elapsed=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' build/large/time.txt)
windows=$(grep -o '[0-9]* windows of' build/large/fit.txt | cut -d' ' -f1)
{
  echo "## Large input: a 10-day log at 10 Hz"
  echo
  echo "Made by \`scripts/large_input.sh\` on $(date -u +%Y-%m-%d): \`gyrotherm fit\` on a simulated"
  echo "240 h record at 10 Hz ($rows rows, $size of CSV; Test 1's INS rig, three holds a day)."
  echo "Files above 64 MB are prepared in one pass (fit/data/streaming.h): read once in blocks of"
  echo "a megabyte, parsed on one thread per core while the glitch filter and the averages run on"
  echo "another, never held."
  echo
  echo "| rows | CSV | windows of 100 s | wall time | peak resident memory |"
  echo "|---|---|---|---|---|"
  echo "| $rows | $size | $windows | $elapsed | $((rss_kb / 1024)) MB |"
  echo
  echo "For scale: holding the rows alone would take $((rows * 3 * 8 / 1048576)) MB (three doubles"
  echo "a row); the averaged series is $((windows * 7 * 8 / 1024)) kB. The peak is the program and"
  echo "its libraries (about 44 MB for any input), the 8 MB prefix of 262 144 rows and the batches"
  echo "in flight, independent of the record's length."
  echo
  echo "The command against the plainest programs on the same bytes, timed in turn in the same run"
  echo "(each the median of 5, from the page cache; MB = 10⁶ bytes):"
  echo
  echo "| command | time | throughput | \`fit\` against it |"
  echo "|---|---|---|---|"
  echo "| \`cat\` (to /dev/null) | $cat_s s | $(per_s "$cat_s") MB/s | $(ratio "$cat_s" "$fit_s") |"
  echo "| \`wc -l\` | $wc_s s | $(per_s "$wc_s") MB/s | $(ratio "$wc_s" "$fit_s") |"
  echo "| \`gyrotherm fit\` | $fit_s s | $(per_s "$fit_s") MB/s | 1 |"
  echo
  echo "The limits, by \`bench_io\` in the same run (medians of 5):"
  echo
  echo "| step on the same bytes | time | throughput | \`fit\` against it |"
  echo "|---|---|---|---|"
  echo "| read the bytes (1 MB blocks) | $(secs BM_LargeLog_Read) s | $read_mbs MB/s | $(ratio "$fit_mbs" "$read_mbs") |"
  echo "| parse alone, one thread (\`for_each_row\`) | $(secs BM_LargeLog_Parse) s | $parse_mbs MB/s | $(ratio "$fit_mbs" "$parse_mbs") |"
  echo "| the preparing thread's work alone (glitch filter, windows; on parsed arrays) | $(secs BM_LargeLog_Filter) s | $filter_mbs MB/s | $(ratio "$fit_mbs" "$filter_mbs") |"
  echo "| \`prepare_csv\`: blocks parsed on every core, filtered on one | $(secs BM_LargeLog_Prepare) s | $prepare_mbs MB/s | $(ratio "$fit_mbs" "$prepare_mbs") |"
  echo "| \`fit\`: read, parse, filter, average, ols | $(secs BM_LargeLog_Fit) s | $fit_mbs MB/s | 1 |"
  echo
  echo "The blocks are parsed on every core while one thread filters and averages; where the"
  echo "cores are shared (this machine's two vCPUs give about 1.25 cores' throughput when both"
  echo "are busy, docs/speed.md) \`prepare_csv\` runs nearer the threads' work added than the"
  echo "slowest thread's."
  echo
  echo '```'
  cat build/large/fit.txt
  echo '```'
} > results/large_input.md
cat results/large_input.md
