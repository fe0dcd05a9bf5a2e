#!/usr/bin/env bash
# Runs the Google Benchmark programs in bench/ and writes their figures to
# results/: one JSON per program (bench_<area>.json) and results/benchmarks.md
# with the machine, the date and each program's table.
#   scripts/bench.sh            all programs
#   scripts/bench.sh sim        only bench_sim
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p results
areas=("$@")
if [ ${#areas[@]} -eq 0 ]; then
  areas=()
  for exe in build/bench/bench_*; do areas+=("${exe##*/bench_}"); done
fi
for area in "${areas[@]}"; do
  echo "bench: $area"
  "build/bench/bench_$area" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_out="results/bench_$area.json.tmp" --benchmark_out_format=json \
    > "results/bench_$area.txt.tmp"
  mv "results/bench_$area.json.tmp" "results/bench_$area.json"
  mv "results/bench_$area.txt.tmp" "results/bench_$area.txt"
done

# The summary page: machine, date, and every program's table.
{
  echo "# Benchmarks"
  echo
  echo "Made by \`scripts/bench.sh\` on $(date -u +%Y-%m-%d) (UTC)."
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'),"
  echo "$(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo) RAM, $(uname -sr)."
  echo "Shared, noisy machines: read ratios measured in one run, not absolute times."
  echo "Each figure is the median/mean of 5 repetitions; raw JSON beside this file."
  for txt in results/bench_*.txt; do
    area=${txt#results/bench_}; area=${area%.txt}
    echo
    echo "## $area"
    echo
    [ -f "bench/README_$area.md" ] && cat "bench/README_$area.md" && echo
    echo '```'
    grep -v '^\*\*\*' "$txt" | sed -n '/^---/,$p'
    echo '```'
  done
} > results/benchmarks.md.tmp
mv results/benchmarks.md.tmp results/benchmarks.md
echo "bench: wrote results/benchmarks.md"
