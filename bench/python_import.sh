#!/usr/bin/env bash
# How long `import tightrope` takes, and where the time goes (issue 46:
# target 0.5 s). Medians of RUNS fresh interpreters, each figure in seconds:
#   interpreter   `python -c pass`, the whole process (the floor)
#   numpy         `import numpy` inside the process (the one dependency)
#   cold          `import tightrope` inside the process, no bytecode cache
#                 for the package (numpy's as installed)
#   warm          the same with the package's __pycache__ written
#   process       the whole `python -c "import tightrope"`, warm
#   ours cold     `import tightrope` after `import numpy` in the same
#   ours warm     process: the package's own share, without numpy's noise
#   first call    make_knot("circle") right after the import (what the
#                 library's loading, done on first use, costs there)
# The package is copied to a temporary folder first (the library inside it
# too), so that the cold runs delete nothing of the installed package.
#   bench/python_import.sh [PYTHON] [RUNS]     (default: python3, 9)
# PYTHON is an interpreter where `import tightrope` works (a venv's
# bin/python after pip install ./python).
set -euo pipefail
py=${1:-python3} runs=${2:-9}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pkg=$("$py" -c "import importlib.util, os; print(os.path.dirname(importlib.util.find_spec('tightrope').origin))")
cp -r "$pkg" "$tmp/tightrope"
rm -rf "$tmp/tightrope/__pycache__"
echo "python: $("$py" -c 'import sys; print(sys.version.split()[0])')  numpy: $("$py" -c 'import numpy; print(numpy.__version__)')  package: $pkg"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)  cores: $(nproc)"
"$py" - "$py" "$runs" "$tmp" <<'EOF'
import os, statistics, subprocess, sys, time
py, runs, tmp = sys.argv[1], int(sys.argv[2]), sys.argv[3]
env = dict(os.environ, PYTHONPATH=tmp, PYTHONDONTWRITEBYTECODE="1")
env.pop("TIGHTROPE_LIBRARY", None)  # the library inside the package
timed = "import time; t = time.perf_counter(); import {m}; print(time.perf_counter() - t)"
first = "import tightrope, time; t = time.perf_counter(); tightrope.make_knot('circle'); print(time.perf_counter() - t)"

def inside(code, e=env):
    r = subprocess.run([py, "-c", code], env=e, capture_output=True, text=True)
    if r.returncode != 0 or not r.stdout.strip():
        sys.exit(f"python_import: {code!r} failed ({r.returncode}): {r.stderr.strip()}")
    return float(r.stdout)

def whole(code, e=env):
    t = time.perf_counter()
    subprocess.run([py, "-c", code], env=e, check=True)
    return time.perf_counter() - t

def median(f):
    return statistics.median(f() for _ in range(runs))

rows = [("interpreter", median(lambda: whole("pass"))), ("numpy", median(lambda: inside(timed.format(m="numpy"))))]
rows.append(("cold", median(lambda: inside(timed.format(m="tightrope")))))
after = "import numpy, time; t = time.perf_counter(); import tightrope; print(time.perf_counter() - t)"
rows.append(("ours cold", median(lambda: inside(after))))
warm = dict(env)
del warm["PYTHONDONTWRITEBYTECODE"]
whole("import tightrope", warm)  # writes the package's __pycache__ (in the copy)
rows.append(("warm", median(lambda: inside(timed.format(m="tightrope"), warm))))
rows.append(("process", median(lambda: whole("import tightrope", warm))))
rows.append(("ours warm", median(lambda: inside(after, warm))))
rows.append(("first call", median(lambda: inside(first, warm))))
for name, v in rows:
    print(f"{name:12s} {v:.3f}")
EOF
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
