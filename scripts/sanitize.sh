#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer and UndefinedBehaviorSanitizer
# (g++, build-asan/) and runs all of it. Any report fails the run.
# This build is configured without MPI: OpenMPI unloads its plugins before exit,
# so their one-off allocations show up as leaks in "<unknown module>" that no
# suppression can name. The MPI path is tested by the normal build
# (scripts/test.sh); this one also proves the MPI-off build compiles and passes.
# Every test runs here except the statistical studies named below.
set -euo pipefail
cd "$(dirname "$0")/.."
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
# -O1 -g1 (line tables only): the sanitizers' own advice for stack traces, and
# half the compile time of -O2 -g on the Eigen-heavy files (93 -> 45 s for
# fit/model/noise_model.cpp); this build is most of CI's time.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGYROTHERM_BUILD_BENCH=OFF -DGYROTHERM_WITH_MPI=OFF -DGYROTHERM_PYTHON=OFF \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  > build-asan.log 2>&1 || { cat build-asan.log; exit 1; }
cmake --build build-asan -j "$(nproc)" >> build-asan.log 2>&1 || { tail -50 build-asan.log; exit 1; }
rm -f build-asan.log
cd build-asan
# The statistical studies (coverage of intervals and false-alarm rates over
# tens of seeds) run the same code paths as the rest of the suite many times
# over; they are judged in the normal build (scripts/test.sh), and left out
# here, where they cost several minutes of the sanitizer run (CI has 60);
# so are plan's whole searches (tens of seconds each in the normal build;
# its refusals and one full search that finds nothing still run here).
studies='IntervalsCover|NineOfTen|UnbiasedAndCovered|UniformPValues|RarelyShowAStep|RecoveryOverSeeds|PlanIsShorterThanEveryRecipe|ThePlanMeetsItsTarget|PredictionMatchesTheSpread'
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "$(nproc)" --timeout 900 -E "$studies"
