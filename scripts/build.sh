#!/usr/bin/env bash
# Configures gyrotherm (Release) in build/ and builds it; later runs are incremental.
#   scripts/build.sh                  every part whose packages are installed (tests,
#                                     benchmarks, Python package: AUTO in CMakeLists.txt)
#   scripts/build.sh TARGET...        only those targets: `gyrotherm` is the program
#                                     (scripts/main.sh), 139 of the 229 files
#   scripts/build.sh --all [TARGET...]  with every part required (scripts/test.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
parts=()
if [ "${1:-}" = "--all" ]; then
  parts=(-DGYROTHERM_BUILD_TESTS=ON -DGYROTHERM_BUILD_BENCH=ON -DGYROTHERM_PYTHON=ON)
  shift
fi
targets=()
for t in "$@"; do targets+=(--target "$t"); done
# Ninja compiles a library's files while the libraries it links are still
# being built (make waits for each); a build folder keeps the generator it
# was made with.
generator=()
if [ ! -f build/CMakeCache.txt ] && command -v ninja > /dev/null; then generator=(-G Ninja); fi
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${parts[@]}" > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j "$(nproc)" "${targets[@]}" 2>&1 | tee -a build.log | grep -E "error|warning|Error" || true
test "${PIPESTATUS[0]}" -eq 0
rm -f build.log
