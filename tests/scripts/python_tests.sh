#!/usr/bin/env bash
# The Python package's tests (python/tests) against the library of this
# build, without installing anything: the package from python/src, the
# library by TIGHTROPE_LIBRARY, the command line (for measure --json) by
# TIGHTROPE_CLI. The interpreter: $TIGHTROPE_PYTHON, else the first python3
# with numpy and pytest (Debian python3-numpy, python3-pytest: scripts/deps.sh).
#   python_tests.sh LIBRARY CLI SOURCE_DIR
set -euo pipefail
lib=$1 cli=$2 src=$3
py=
for p in ${TIGHTROPE_PYTHON:-} /usr/bin/python3 python3; do
  if command -v "$p" >/dev/null && "$p" -c "import numpy, pytest" 2>/dev/null; then
    py=$p
    break
  fi
done
if [ -z "$py" ]; then
  echo "python_tests: skipped: no python3 with numpy and pytest (scripts/deps.sh installs python3-numpy python3-pytest)"
  exit 77
fi
export TIGHTROPE_LIBRARY=$lib TIGHTROPE_CLI=$cli PYTHONPATH=$src/python/src${PYTHONPATH:+:$PYTHONPATH}
export PYTHONDONTWRITEBYTECODE=1
exec "$py" -m pytest -q -p no:cacheprovider "$src/python/tests"
