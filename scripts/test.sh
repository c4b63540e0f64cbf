#!/usr/bin/env bash
# Installs missing packages, builds, and runs the whole test suite.
#   scripts/test.sh              normal build in build/
#   scripts/test.sh --sanitize   -fsanitize=address,undefined build in build-asan/
#   scripts/test.sh --oclgrind   the OpenCL tests under Oclgrind (installed if missing) in
#                                build-oclgrind/: scripts/oclgrind_run.sh fails on any report
#   scripts/test.sh --python     the Python package as a user installs it: pip install ./python
#                                in a fresh venv (build-python/venv), then its pytest tests
#                                against the installed package (the normal run's ctest already
#                                runs them against build/'s library, label python)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--python" ]; then
  bash scripts/deps.sh
  # pip builds the package from PyPI's scikit-build-core and cmake: without a
  # package index there is nothing to test here (the normal run's ctest has
  # already run the package's tests against build/'s library), said loudly
  index=${PIP_INDEX_URL:-https://pypi.org/simple}
  if ! python3 -c "import sys, urllib.request; urllib.request.urlopen(sys.argv[1] + '/scikit-build-core/', timeout=20)" "$index" 2>/dev/null; then
    echo "scripts/test.sh --python: SKIPPED: no package index at $index (pip install ./python needs one)" >&2
    exit 0
  fi
  rm -rf build-python
  python3 -m venv build-python/venv
  start=$(date +%s)
  build-python/venv/bin/pip install --quiet ./python pytest
  echo "pip install ./python pytest: $(( $(date +%s) - start )) s"
  # from outside the source tree, so that "import tightrope" is the installed package;
  # the command line of the normal run (if built) for the measure --json comparison
  cd build-python
  [ -x ../build/tightrope ] && export TIGHTROPE_CLI=$PWD/../build/tightrope
  exec venv/bin/python -m pytest -q -p no:cacheprovider ../python/tests
fi
if [ "${1:-}" = "--oclgrind" ]; then
  bash scripts/deps.sh oclgrind
  # only what the leg runs: the OpenCL tests (label backend/opencl, at their
  # small sizes) and the broken kernels it must catch (label oclgrind)
  cmake -S . -B build-oclgrind -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTIGHTROPE_OCLGRIND=ON
  cmake --build build-oclgrind -j"$(nproc)" --target opencl_tests
  cd build-oclgrind
  exec ctest --output-on-failure --no-tests=error -j"$(nproc)" -L '^(backend/opencl|oclgrind)$'
fi
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
if ctest --output-on-failure --no-tests=error -j"$(nproc)"; then
  exit 0
fi
# LeakSanitizer's tracer now and then dies at exit while it stops the threads
# (PoCL's workers) to scan them: "Tracer caught signal 11 ... LeakSanitizer
# has encountered a fatal error", after every check of the test has passed
# (google/sanitizers#1353). Only then, the failed tests run once more; a real
# failure fails again.
if [ "$dir" = build-asan ] && grep -q "LeakSanitizer has encountered a fatal error" \
    Testing/Temporary/LastTest.log; then
  echo "LeakSanitizer's tracer crashed at exit; running the failed tests once more"
  ctest --output-on-failure --no-tests=error --rerun-failed
else
  exit 1
fi
