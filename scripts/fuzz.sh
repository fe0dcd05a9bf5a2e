#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/) with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer in build-fuzz/, and runs each for SECONDS
# (default 60) on a corpus seeded from the shipped files. A crash, leak or
# sanitizer report fails the script and leaves the input in
# build-fuzz/artifacts/; turn it into a regression test.
#   scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined -fno-omit-frame-pointer -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
generator=()  # Ninja when there is one (scripts/build.sh)
if [ ! -f build-fuzz/CMakeCache.txt ] && command -v ninja > /dev/null; then generator=(-G Ninja); fi
# -O1 with line tables, as libFuzzer's own documentation builds its targets.
CC=clang CXX=clang++ cmake -S . -B build-fuzz "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DGYROTHERM_FUZZ=ON -DGYROTHERM_BUILD_TESTS=OFF -DGYROTHERM_BUILD_BENCH=OFF -DGYROTHERM_PYTHON=OFF \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" > build-fuzz.log 2>&1 || { cat build-fuzz.log; exit 1; }
cmake --build build-fuzz -j "$(nproc)" --target fuzz_csv fuzz_toml fuzz_formula fuzz_ulog fuzz_dataflash >> build-fuzz.log 2>&1 || { tail -50 build-fuzz.log; exit 1; }
rm -f build-fuzz.log

mkdir -p build-fuzz/artifacts
# One target per core at a time, each for SECONDS: the same fuzzing, in less
# wall time. A target's output goes to build-fuzz/TARGET.log, shown at the end.
fuzz_one() {
  local target=$1 corpus="build-fuzz/corpus/$1"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "build-fuzz/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="build-fuzz/artifacts/${target}-" -print_final_stats=1 \
    "$corpus" > "build-fuzz/$target.log" 2>&1
}
targets="csv toml formula ulog dataflash"
for target in $targets; do
  corpus="build-fuzz/corpus/$target"
  mkdir -p "$corpus"
  cp tests/fuzz/corpus/$target/* "$corpus/"
  if [ "$target" = toml ]; then cp scenarios/*.toml "$corpus/"; fi
  if [ "$target" = csv ] && [ -x build/app/gyrotherm ]; then
    # A short simulated record as a realistic seed.
    build/app/gyrotherm simulate scenarios/warmup.toml -o build-fuzz/seed.csv > /dev/null
    head -c 20000 build-fuzz/seed.csv > "$corpus/simulated.csv"
  fi
done
failed=0
set -- $targets
while [ $# -gt 0 ]; do
  batch=()
  for _ in $(seq "$(nproc)"); do
    [ $# -gt 0 ] || break
    batch+=("$1")
    shift
  done
  pids=()
  for target in "${batch[@]}"; do
    echo "fuzz: $target for ${seconds} s"
    fuzz_one "$target" &
    pids+=($!)
  done
  for k in "${!pids[@]}"; do
    status=0
    wait "${pids[$k]}" || status=$?
    tail -n 12 "build-fuzz/${batch[$k]}.log"
    if [ "$status" -ne 0 ]; then
      echo "fuzz: ${batch[$k]} failed (exit $status); its input is in build-fuzz/artifacts/"
      failed=1
    fi
  done
done
[ "$failed" -eq 0 ]
echo "fuzz: no crash, leak or sanitizer report"
