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
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGYROTHERM_FUZZ=ON -DGYROTHERM_BUILD_TESTS=OFF -DGYROTHERM_BUILD_BENCH=OFF \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" > build-fuzz.log 2>&1 || { cat build-fuzz.log; exit 1; }
cmake --build build-fuzz -j "$(nproc)" --target fuzz_csv fuzz_toml fuzz_formula fuzz_ulog fuzz_dataflash >> build-fuzz.log 2>&1 || { tail -50 build-fuzz.log; exit 1; }
rm -f build-fuzz.log

mkdir -p build-fuzz/artifacts
for target in csv toml formula ulog dataflash; do
  corpus="build-fuzz/corpus/$target"
  mkdir -p "$corpus"
  cp tests/fuzz/corpus/$target/* "$corpus/"
  if [ "$target" = toml ]; then cp scenarios/*.toml "$corpus/"; fi
  if [ "$target" = csv ] && [ -x build/app/gyrotherm ]; then
    # A short simulated record as a realistic seed.
    build/app/gyrotherm simulate scenarios/warmup.toml -o build-fuzz/seed.csv > /dev/null
    head -c 20000 build-fuzz/seed.csv > "$corpus/simulated.csv"
  fi
  echo "fuzz: $target for ${seconds} s"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "build-fuzz/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="build-fuzz/artifacts/${target}-" -print_final_stats=1 \
    "$corpus" 2>&1 | tail -n 12
  test "${PIPESTATUS[0]}" -eq 0
done
echo "fuzz: no crash, leak or sanitizer report"
