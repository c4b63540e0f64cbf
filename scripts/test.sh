#!/usr/bin/env bash
# Installs missing packages, builds, and runs the whole test suite.
#   scripts/test.sh              normal build in build/
#   scripts/test.sh --sanitize   -fsanitize=address,undefined build in build-asan/
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
dir=build
opts=(-DCMAKE_BUILD_TYPE=RelWithDebInfo)
if [ "${1:-}" = "--sanitize" ]; then
  dir=build-asan
  opts=(-DCMAKE_BUILD_TYPE=Debug -DTIGHTROPE_SANITIZE=ON)
  # PoCL and the ICD loader keep allocations alive until exit; their leaks are not ours.
  export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
fi
cmake -S . -B "$dir" "${opts[@]}" -DTIGHTROPE_FUZZ=ON
cmake --build "$dir" -j"$(nproc)"
cd "$dir"
ctest --output-on-failure --no-tests=error -j"$(nproc)"
