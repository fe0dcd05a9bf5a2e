#!/usr/bin/env bash
# Runs the Google Benchmark programs in bench/ and writes their figures to
# results/: one JSON per program (bench_<area>.json) and results/benchmarks.md
# with the machine, the date, a table of the ratios that matter, and each
# program's table. With the score area it also times 100-trial campaigns of
# `gyrotherm score` on the cycle (results/bench_score_campaign*.json).
#   scripts/bench.sh            all programs
#   scripts/bench.sh sim        only bench_sim
# Needs bash, awk and the build; with the table area also Debian's
# /usr/bin/python3 and the Python package (bench/python_fit_bench.py:
# gyrotherm.fit on 10⁷ samples in numpy arrays against BM_FitTable on the same
# arrays, results/bench_python_fit.json).
set -euo pipefail
cd "$(dirname "$0")/.."
areas=("$@")
known=$(ls bench/*_bench.cpp | sed 's|bench/||; s|_bench.cpp||' | tr '\n' ' ')
for area in "${areas[@]}"; do
  case " $known" in
    *" $area "*) ;;
    *) echo "usage: scripts/bench.sh [AREA ...]; areas: $known(none: all)" >&2; exit 2 ;;
  esac
done
scripts/build.sh
mkdir -p results
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

# The large-log limits (results/large_input.md, results/bench_large.json):
# with every area, or with io.
for area in "${areas[@]}"; do
  [ "$area" = io ] && scripts/large_input.sh > /dev/null
done

# gyrotherm.fit from Python on the same arrays as the C++ library's fit.
for area in "${areas[@]}"; do
  [ "$area" = table ] || continue
  echo "bench: gyrotherm.fit (Python) on 10^7 samples against BM_FitTable"
  PYTHONPATH=build/python /usr/bin/python3 bench/python_fit_bench.py --json results/bench_python_fit.json.tmp > /dev/null
  mv results/bench_python_fit.json.tmp results/bench_python_fit.json
done

# The issue's campaign target: 100 trials of the cycle, every engine, in
# under a minute; on 1 and on 2 threads (the scoreboards are identical).
for area in "${areas[@]}"; do
  [ "$area" = score ] || continue
  for threads in 1 2; do
    echo "bench: gyrotherm score, 100 trials of the cycle on $threads thread(s)"
    build/app/gyrotherm score scenarios/cycle.toml --trials 100 --threads "$threads" --json \
      2> /dev/null > "results/bench_score_campaign$threads.json.tmp"
    mv "results/bench_score_campaign$threads.json.tmp" "results/bench_score_campaign$threads.json"
  done
done

# bench_field FILE BENCHMARK FIELD: a number from Google Benchmark's JSON
# (one key per line); empty when the file or the benchmark is missing.
bench_field() {
  [ -f "$1" ] || return 0
  awk -v name="\"name\": \"$2\"," -v field="\"$3\":" '
    index($0, name) { inside = 1; next }
    inside && index($0, field) { sub(/^[^:]*: */, ""); sub(/,$/, ""); print; exit }
    inside && /^ *}/ { inside = 0 }' "$1"
}
# run_seconds FILE: the wall time in the "run" object of a `score --json`.
run_seconds() {
  [ -f "$1" ] || return 0
  awk '/"run": \{/ { inside = 1 } inside && /"seconds":/ { sub(/^[^:]*: */, ""); sub(/,$/, ""); print; exit }' "$1"
}
# ratio A B FORMAT: A/B, or – when either is missing.
ratio() {
  if [ -z "$1" ] || [ -z "$2" ]; then echo "–"; else awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN { printf f, a / b }'; fi
}
show() {
  if [ -z "$1" ]; then echo "–"; else awk -v a="$1" -v f="$2" 'BEGIN { printf f, a }'; fi
}
megabytes() {
  if [ -z "$1" ]; then echo "–"; else awk -v a="$1" 'BEGIN { printf "%.0f MB/s", a / 1e6 }'; fi
}

fit=results/bench_fit.json
score=results/bench_score.json
io=results/bench_io.json
gram4=$(bench_field $fit BM_ObjectiveGram/10000_median real_time)
naive4=$(bench_field $fit BM_ObjectiveNaive/10000_median real_time)
gram5=$(bench_field $fit BM_ObjectiveGram/100000_median real_time)
naive5=$(bench_field $fit BM_ObjectiveNaive/100000_median real_time)
declare -A evals ms reached
for e in iafsa pso cmaes; do
  evals[$e]=$(bench_field $fit "BM_EngineToTarget/${e}_median" evals_median)
  ms[$e]=$(bench_field $fit "BM_EngineToTarget/${e}_median" real_time)
  reached[$e]=$(bench_field $fit "BM_EngineToTarget/${e}_median" reached_of_10)
done
speedup=$(bench_field $score BM_CampaignSpeedup/real_time_median speedup)
ceiling=$(bench_field $score BM_CampaignSpeedup/real_time_median ceiling)
one_thread=$(bench_field $score BM_CampaignSpeedup/real_time_median seconds_1_thread)
two_threads=$(bench_field $score BM_CampaignSpeedup/real_time_median seconds_2_threads)
campaign1=$(run_seconds results/bench_score_campaign1.json)
campaign2=$(run_seconds results/bench_score_campaign2.json)
read_bps=$(bench_field $io BM_ReadMeasurementCsv/real_time_median bytes_per_second)
write_bps=$(bench_field $io BM_WriteSimulationCsv/real_time_median bytes_per_second)
sim=results/bench_sim.json
large=results/bench_large.json
sim_median=$(bench_field $sim BM_SimulateProfile/random_72h/real_time_median real_time)
sim_min=$(bench_field $sim BM_SimulateProfile/random_72h/real_time_min real_time)
thermal_median=$(bench_field $sim BM_ThermalOnly/random_72h_median real_time)
thermal_min=$(bench_field $sim BM_ThermalOnly/random_72h_min real_time)
format_bps=$(bench_field $io BM_FormatSimulationCsv/real_time_median bytes_per_second)
large_read=$(bench_field $large BM_LargeLog_Read/iterations:1/real_time_median bytes_per_second)
large_parse=$(bench_field $large BM_LargeLog_Parse/iterations:1/real_time_median bytes_per_second)
large_fit=$(bench_field $large BM_LargeLog_Fit/iterations:1/real_time_median bytes_per_second)
large_fit_ms=$(bench_field $large BM_LargeLog_Fit/iterations:1/real_time_median real_time)
diag=results/bench_diagnose.json
diag72=$(bench_field $diag BM_Diagnose/random_72h/iterations:1_median real_time)
diag10=$(bench_field $diag BM_Diagnose/ten_days/iterations:1_median real_time)
fit72=$(bench_field $diag BM_Fit/random_72h_median real_time)
fit10=$(bench_field $diag BM_Fit/ten_days_median real_time)
plan=results/bench_plan.json
plan3=$(bench_field $plan BM_Plan/3/iterations:1/real_time_median real_time)
plan6=$(bench_field $plan BM_Plan/6/iterations:1/real_time_median real_time)
plan6_evals=$(bench_field $plan BM_Plan/6/iterations:1/real_time_median evaluations)
predict6=$(bench_field $plan BM_PredictPrecision/6/real_time_median real_time)
# json_number FILE KEY: a number from a flat JSON object (bench_python_fit.json).
json_number() {
  [ -f "$1" ] || return 0
  awk -v key="\"$2\":" 'index($0, key) { sub(/^[^:]*: */, ""); sub(/,$/, ""); print; exit }' "$1"
}
commands=results/bench_large_commands.json
cmd_bytes=$(json_number $commands file_bytes)
cmd_cat=$(json_number $commands cat_s)
cmd_wc=$(json_number $commands wc_l_s)
cmd_fit=$(json_number $commands fit_s)
pyfit=results/bench_python_fit.json
py_s=$(json_number $pyfit python_fit_cpu_s)
cpp_s=$(json_number $pyfit cpp_fit_cpu_s)
py_extra=$(json_number $pyfit peak_beyond_arrays_mb)
py_arrays=$(json_number $pyfit arrays_mb)
table=results/bench_table.json
table_fit=$(bench_field $table BM_FitTable/10000000/iterations:1_median cpu_time)
table_run=$(bench_field $table BM_RunFitTable/10000000/iterations:1_median cpu_time)
declare -A per_trial
for n in 100 1000 10000; do
  per_trial[$n]=$(bench_field $score "BM_CampaignScaling/$n/iterations:1/repeats:1/real_time" ms_per_trial)
done

# The summary page: machine, date, the ratios, and every program's table.
{
  echo "# Benchmarks"
  echo
  echo "Made by \`scripts/bench.sh\` on $(date -u +%Y-%m-%d) (UTC)."
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'),"
  echo "$(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo) RAM, $(uname -sr)."
  echo "Shared, noisy machines: read ratios measured in one run, not absolute times."
  echo "Each figure is the median/mean of 5 repetitions; raw JSON beside this file."
  echo
  echo "## Each figure against its limit"
  echo
  echo "| figure (aim) | measured | its limit | figure / limit |"
  echo "|---|---|---|---|"
  echo "| \`fit\` on the 10-day 10 Hz log, 583 MB (≤ 2 s, ≥ 250 MB/s) | $(show "$large_fit_ms" "%.0f") ms, $(megabytes "$large_fit") | reading the bytes from the page cache: $(megabytes "$large_read") | $(ratio "$large_fit" "$large_read" "%.2f") |"
  echo "| the same | | parsing alone, one thread: $(megabytes "$large_parse") | $(ratio "$large_fit" "$large_parse" "%.2f") |"
  echo "| \`gyrotherm fit\` on it, the command (≥ 700 MB/s on 2 cores; aim 1 GB/s) | $(show "$cmd_fit" "%.2f") s, $(megabytes "$(ratio "$cmd_bytes" "$cmd_fit" "%.0f")") | \`wc -l\` of the same file in the same run: $(show "$cmd_wc" "%.3f") s, $(megabytes "$(ratio "$cmd_bytes" "$cmd_wc" "%.0f")") | $(ratio "$cmd_wc" "$cmd_fit" "%.2f") |"
  echo "| the same | | \`cat\` of it: $(show "$cmd_cat" "%.3f") s, $(megabytes "$(ratio "$cmd_bytes" "$cmd_cat" "%.0f")") | $(ratio "$cmd_cat" "$cmd_fit" "%.2f") |"
  echo "| simulating 72 h at 1 Hz, noise included (≤ 40 ms): median, fastest of 5 | $(show "$sim_median" "%.1f"), $(show "$sim_min" "%.1f") ms | integrating alone (CVODE and the samples' states): $(show "$thermal_median" "%.1f"), $(show "$thermal_min" "%.1f") ms | $(ratio "$sim_median" "$thermal_median" "%.2f"), $(ratio "$sim_min" "$thermal_min" "%.2f") |"
  echo "| writing a 72 h record's CSV (≥ 250 MB/s) | $(megabytes "$write_bps") | formatting it in memory: $(megabytes "$format_bps") | $(ratio "$write_bps" "$format_bps" "%.2f") |"
  echo "| a 10-trial campaign on 2 threads (≥ 1.8× one thread) | $(show "$two_threads" "%.2f") s | one thread: $(show "$one_thread" "%.2f") s, over 2: $(show "$one_thread" "%.2f") / 2 s; the machine's own 2-thread speed-up now $(show "$ceiling" "%.2f×") | speed-up $(show "$speedup" "%.2f×") |"
  echo "| \`diagnose\` on the 72 h record (≤ 1.5 s) | $(show "$diag72" "%.0f") ms | \`fit\` on the same: $(show "$fit72" "%.0f") ms | $(ratio "$diag72" "$fit72" "%.1f") |"
  echo "| \`diagnose\` on 10 days (≤ 5 s) | $(show "$diag10" "%.0f") ms | \`fit\` on the same: $(show "$fit10" "%.0f") ms | $(ratio "$diag10" "$fit10" "%.1f") |"
  echo "| \`plan\` for six terms (≤ 60 s on 2 cores) | $(show "$plan6" "%.1f") s ($(show "$plan6_evals" "%.0f") predictions; the paper's three terms: $(show "$plan3" "%.1f") s) | the aim, 60 s | $(ratio "$plan6" 60 "%.2f") |"
  echo "| the same | | its predictions one after another: $(show "$plan6_evals" "%.0f") × $(show "$predict6" "%.1f") ms (one on the 8.8 h cycle) | $(awk -v a="$plan6" -v n="$plan6_evals" -v p="$predict6" 'BEGIN { if (a == "" || n == "" || p == "") print "–"; else printf "%.2f", a / (n * p / 1000) }') |"
  echo "| \`gyrotherm.fit\` (Python) on 10⁷ samples in numpy arrays (≤ 1.2× the C++ library's fit of the same arrays), CPU time | $(show "$py_s" "%.2f") s | \`bench_table\` BM_FitTable on the same arrays: $(show "$cpp_s" "%.2f") s | $(ratio "$py_s" "$cpp_s" "%.2f") |"
  echo "| the same in C++: the library's whole \`fit\` (studies::run_fit: the command's defaults, JSON and report) on the arrays, CPU time | $(show "$table_run" "%.2f") s | \`bench_table\` BM_FitTable (prepare_table + fit_model alone): $(show "$table_fit" "%.2f") s | $(ratio "$table_run" "$table_fit" "%.2f") |"
  echo "| its peak memory beyond the arrays (≤ 64 MB) | $(show "$py_extra" "%.0f") MB (the arrays: $(show "$py_arrays" "%.0f") MB) | the aim, 64 MB | $(ratio "$py_extra" 64 "%.2f") |"
  echo "| campaign time per trial, 10,000 trials (linear growth) | $(show "${per_trial[10000]}" "%.1f") ms | per trial at 100 trials: $(show "${per_trial[100]}" "%.1f") ms | $(ratio "${per_trial[10000]}" "${per_trial[100]}" "%.2f") |"
  echo
  echo "## The ratios that matter"
  echo
  echo "| question | ratio | measured by |"
  echo "|---|---|---|"
  echo "| σ from the Gram matrix vs from every residual, 10⁴ points | $(ratio "$naive4" "$gram4" "%.0f×") faster | \`bench_fit\` BM_ObjectiveNaive / BM_ObjectiveGram |"
  echo "| the same, 10⁵ points | $(ratio "$naive5" "$gram5" "%.0f×") faster | \`bench_fit\` |"
  echo "| evaluations to 1e-6 of the optimum: pso / iafsa | $(ratio "${evals[pso]}" "${evals[iafsa]}" "%.2f") ($(show "${evals[pso]}" "%.0f") vs $(show "${evals[iafsa]}" "%.0f")) | \`bench_fit\` BM_EngineToTarget, median of 10 seeds |"
  echo "| evaluations to 1e-6 of the optimum: cmaes / iafsa | $(ratio "${evals[cmaes]}" "${evals[iafsa]}" "%.2f") ($(show "${evals[cmaes]}" "%.0f") vs $(show "${evals[iafsa]}" "%.0f")) | \`bench_fit\` BM_EngineToTarget |"
  echo "| seconds to 1e-6 of the optimum: pso / iafsa | $(ratio "${ms[pso]}" "${ms[iafsa]}" "%.2f") ($(show "${ms[pso]}" "%.2f") vs $(show "${ms[iafsa]}" "%.2f") ms for 10 fits) | \`bench_fit\` BM_EngineToTarget |"
  echo "| seconds to 1e-6 of the optimum: cmaes / iafsa | $(ratio "${ms[cmaes]}" "${ms[iafsa]}" "%.2f") ($(show "${ms[cmaes]}" "%.2f") vs $(show "${ms[iafsa]}" "%.2f") ms) | \`bench_fit\` BM_EngineToTarget |"
  echo "| seeds reaching the target (of 10): iafsa, pso, cmaes | $(show "${reached[iafsa]}" "%.0f"), $(show "${reached[pso]}" "%.0f"), $(show "${reached[cmaes]}" "%.0f") | \`bench_fit\` BM_EngineToTarget |"
  echo "| campaign speed-up, 1 → 2 threads (10 trials, every engine; aim ≥ 1.8) | $(show "$speedup" "%.2f×") ($(show "$one_thread" "%.2f") s vs $(show "$two_threads" "%.2f") s; the machine's ceiling then, a pure arithmetic loop: $(show "$ceiling" "%.2f×")) | \`bench_score\` BM_CampaignSpeedup |"
  echo "| 100-trial campaign of the cycle, every engine (aim < 60 s) | $(show "$campaign2" "%.1f") s on 2 threads, $(show "$campaign1" "%.1f") s on 1 ($(ratio "$campaign1" "$campaign2" "%.2f×")) | \`gyrotherm score scenarios/cycle.toml --trials 100 --threads N\` |"
  echo "| campaign time per trial at 100 / 1,000 / 10,000 trials (2 threads, every engine; equal if time grows linearly) | $(show "${per_trial[100]}" "%.1f") / $(show "${per_trial[1000]}" "%.1f") / $(show "${per_trial[10000]}" "%.1f") ms ($(ratio "${per_trial[10000]}" "${per_trial[100]}" "%.2f") from 100 to 10,000) | \`bench_score\` BM_CampaignScaling |"
  echo "| CSV of a 72 h run: reading, writing | $(megabytes "$read_bps"), $(megabytes "$write_bps") | \`bench_io\` |"
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
  if [ -f results/large_input.md ]; then
    echo
    sed 's/^## /## /' results/large_input.md
  fi
} > results/benchmarks.md.tmp
mv results/benchmarks.md.tmp results/benchmarks.md
echo "bench: wrote results/benchmarks.md"
