#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer and UndefinedBehaviorSanitizer
# (g++, build-asan/) and runs all of it. Any report fails the run.
# This build is configured without MPI: OpenMPI unloads its plugins before exit,
# so their one-off allocations show up as leaks in "<unknown module>" that no
# suppression can name. The MPI path is tested by the normal build
# (scripts/test.sh); this one also proves the MPI-off build compiles and passes.
# Every test runs here except the statistical studies named below.
# On failure: the failing shard's log (build-asan/shardN.log) is shown.
set -euo pipefail
cd "$(dirname "$0")/.."
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
# -O1 -g1 (line tables only): the sanitizers' own advice for stack traces, and
# half the compile time of -O2 -g on the Eigen-heavy files (93 -> 45 s for
# fit/model/noise_model.cpp); this build is most of CI's time.
# The test files themselves are compiled without the instrumentation
# (GYROTHERM_UNINSTRUMENTED_TESTS, tests/CMakeLists.txt): the libraries and
# the program, which they drive, carry it; it more than doubled the test
# files' compile time.
generator=()  # Ninja when there is one (scripts/build.sh)
if [ ! -f build-asan/CMakeCache.txt ] && command -v ninja > /dev/null; then generator=(-G Ninja); fi
cmake -S . -B build-asan "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGYROTHERM_BUILD_TESTS=ON -DGYROTHERM_BUILD_BENCH=OFF -DGYROTHERM_WITH_MPI=OFF -DGYROTHERM_PYTHON=OFF \
  -DGYROTHERM_UNINSTRUMENTED_TESTS=ON \
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
# its refusals and one full search that finds nothing still run here), and
# the step cases on the 75 h random profile (about 55 s each here; the
# cycle's cases run the same code). Cases that repeat one code path over
# effects, step times or seeds run once here (the rest in the normal build):
# of the per-effect diagnoses only grad's (the one with a second
# temperature), of the cycle's step cases only 19800_up, of the end-to-end
# polynomial terms none beyond T^3; and the three slowest diagnose cases
# (40-65 s each here), whose paths the other diagnose cases run.
studies='IntervalsCover|NineOfTen|EightOfTen|UnbiasedAndCovered|UniformPValues|PValuesAreUniform|DrawnIntoTheNull|RarelyShowAStep|RecoveryOverSeeds|PlanIsShorterThanEveryRecipe|ThePlanMeetsItsTarget|PredictionMatchesTheSpread|NotPassedOffAsDrift/random'
studies+='|ReachesTheFloor/t|ReachesTheFloor/warmup|ReachesTheFloor/hyst|ReachesTheFloor/T_3|ReachesTheFloor/T_dT|ReachesTheFloor/d2T'
studies+='|NotPassedOffAsDrift/cycle_7200_up|NotPassedOffAsDrift/cycle_25200_down|TemperatureFourth.WorksEndToEnd|TemperatureFifth.WorksEndToEnd'
studies+='|CExport.EveryTermAtOnce|NamedFirstOrGroupedNeverTheLagAlone|AnotherGyroAxisIsNoCauseUnlessNamed|DriftOnAMonotoneWarmUpCannotBeToldFromTemperature'
# report's round trip runs fit, compensate, allan, diagnose and check five
# times over, and its random-profile page simulates 75 h first (its first
# case and its refusals run here).
studies+='|ARoundTripOnAUlogWithACheckAndAFitMadeHere|TheRandomProfileHasItsPage'
# check's and the unit checks' round trips fit and export before they check
# (seconds each here); the failure modes and refusals run sanitized.
studies+='|CliCheck.Px4Parameters|CliCheck.MaxResidual|CliCheck.ArduPilotParameters|CliCheck.AFitFile|EveryCommandThatReadsTheRecordChecksItsUnits'
# The program's tests in one process per core (GoogleTest's sharding) rather
# than ctest's process per test: 600 starts of the sanitized program cost
# 0.2 s each (270 s against 326 s for the whole run on 2 cores). The normal
# build (scripts/test.sh) runs each test in a process of its own; here they
# also run one after another in a process, and LeakSanitizer checks each
# process at its exit. Every test here is a GoogleTest one (the Python tests
# are not in this build).
exclude=$(echo "$studies" | tr '|' '\n' | sed 's/.*/*&*/' | paste -sd:)
shards=$(nproc)
rm -f shard*.log premature*
pids=()
# A shard stuck for 20 minutes (a whole shard takes about 5) is stopped; a
# test that ends its process early, even with status 0, leaves GoogleTest's
# premature-exit file behind and fails the run.
for ((i = 0; i < shards; i++)); do
  GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$i TEST_PREMATURE_EXIT_FILE="$PWD/premature$i" \
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    timeout -k 30 1200 tests/gyrotherm_tests --gtest_filter="-$exclude" > "shard$i.log" 2>&1 &
  pids+=($!)
done
failed=0
for i in "${!pids[@]}"; do
  status=0
  wait "${pids[$i]}" || status=$?
  if [ "$status" -eq 0 ] && [ -e "premature$i" ]; then status=99; fi
  if [ "$status" -ne 0 ]; then
    failed=1
    echo "sanitize: shard $i of $shards failed (exit $status; 124: over 20 minutes; 99: a test ended the process early); its log, build-asan/shard$i.log, ends:"
    grep -E "^\[  FAILED  \]|ERROR: AddressSanitizer|ERROR: LeakSanitizer|runtime error" "shard$i.log" | head -40 || true
    tail -n 80 "shard$i.log"
  fi
done
grep -h -E "^\[  PASSED  \]|^\[  SKIPPED \] [0-9]" shard*.log || true
[ "$failed" -eq 0 ]
echo "sanitize: every test passed under AddressSanitizer and UndefinedBehaviorSanitizer"
