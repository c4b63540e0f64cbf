#!/usr/bin/env bash
# OpenCL backend throughput against the serial reference (figures in bench/RESULTS.md).
#   bench/opencl_bench.sh [BUILD_DIR]
# 1) the step with the neighbour search (both backends walk an edge tree,
#    linear in N), N = 10^3 .. 10^6;
# 2) the step alone (--no-search), N = 10^3 .. 10^6;
# 3) the same as JSON, for scripts.
set -euo pipefail
b=${1:-build}
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$b/pocl-cache}
"$b/tightrope" devices
"$b/tightrope" bench --n 1e3,1e4,1e5,1e6 --time 2
"$b/tightrope" bench --n 1e3,1e4,1e5,1e6 --time 2 --no-search
"$b/tightrope" bench --n 1e3,1e4,1e5,1e6 --time 2 --no-search --no-kernels --json > "$b/opencl_bench.json"
echo "JSON: $b/opencl_bench.json"
