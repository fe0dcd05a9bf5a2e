#!/usr/bin/env bash
# Configures and builds gyrotherm (Release) in build/; later runs are incremental.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j "$(nproc)" 2>&1 | tee -a build.log | grep -E "error|warning|Error" || true
test "${PIPESTATUS[0]}" -eq 0
rm -f build.log
