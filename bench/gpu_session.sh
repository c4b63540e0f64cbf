#!/usr/bin/env bash
# Everything the OpenCL figures of bench/RESULTS.md need on a machine with a GPU,
# in as few calls as a short lease allows:
#   bench/gpu_session.sh PHASE... [-- OUTDIR]
# PHASE: setup (find the vendor's OpenCL, build in build-gpu), test (ctest),
#        bench (tightrope bench with and without the neighbour search),
#        e2e (N = 2400 trefoil to 32.7435 on the GPU, on the GPU at every level, and on
#        the reference, side by side).
# Logs go to $OUT (or OUTDIR, default /tmp/gpu-out).
set -uo pipefail
cd "$(dirname "$0")/.."
phases=()
while [ $# -gt 0 ]; do
  case $1 in
    --) shift; OUT=$1; shift ;;
    *) phases+=("$1"); shift ;;
  esac
done
OUT=${OUT:-/tmp/gpu-out}
mkdir -p "$OUT"
b=build-gpu
tr=$b/tightrope

setup() {
  nvidia-smi -L || true
  # the reference data beside the checkout (../shared) does not travel: a copy may be carried in .gpu/
  local shared=../shared
  [ -d $shared/data ] || shared=.gpu/shared
  echo "cores: $(nproc)"; gcc --version | head -1; cmake --version | head -1
  # The driver ships the ICD (libnvidia-opencl); containers often lack the
  # /etc/OpenCL/vendors entry that lets a loader find it.
  local icd
  icd=$(ldconfig -p | awk '/libnvidia-opencl\.so\.1/ {print $NF; exit}')
  [ -n "$icd" ] || icd=$(find / -xdev -name 'libnvidia-opencl.so*' 2>/dev/null | head -1)
  echo "vendor ICD: ${icd:-none}"
  ls /etc/OpenCL/vendors 2>/dev/null
  if [ -n "$icd" ] && ! grep -qs nvidia /etc/OpenCL/vendors/*.icd; then
    mkdir -p /etc/OpenCL/vendors && echo "$icd" > /etc/OpenCL/vendors/nvidia.icd
  fi
  # Headers and loader: the system's, else CUDA's, else the copies carried in .gpu/.
  local inc lib
  for d in /usr/include /usr/local/cuda/include .gpu/include; do
    [ -f "$d/CL/cl.h" ] && { inc=$(realpath "$d"); break; }
  done
  lib=$(ldconfig -p | awk '/libOpenCL\.so\.1 / {print $NF; exit}')
  [ -n "$lib" ] || lib=$(ls /usr/local/cuda/lib64/libOpenCL.so.1 /usr/local/cuda/targets/x86_64-linux/lib/libOpenCL.so.1 2>/dev/null | head -1)
  [ -n "$lib" ] || lib=$(realpath .gpu/lib/libOpenCL.so.1)
  echo "headers: $inc  loader: $lib"
  export LD_LIBRARY_PATH=$(dirname "$lib")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  cmake -S . -B $b -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTIGHTROPE_SHARED_DIR="$(realpath $shared)" \
    -DOpenCL_INCLUDE_DIR="$inc" -DOpenCL_LIBRARY="$lib" > "$OUT/cmake.log" 2>&1 \
    || { tail -20 "$OUT/cmake.log"; return 1; }
  cmake --build $b -j "$(nproc)" > "$OUT/build.log" 2>&1 || { tail -30 "$OUT/build.log"; return 1; }
  echo "$(dirname "$lib")" > $b/opencl-loader-dir
  $tr devices
}

loader_path() {
  [ -f $b/opencl-loader-dir ] && export LD_LIBRARY_PATH=$(cat $b/opencl-loader-dir)${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
}

run_tests() {
  (cd $b && ctest -j 8 --output-on-failure > "$OUT/ctest.log" 2>&1)
  local rc=$?
  grep -E "tests passed|Failed|\*\*\*" "$OUT/ctest.log" | tail -20
  # the kernel validations print the device they ran on and their largest differences
  (cd $b && ./tests/test_opencl_backend 2>&1 | tail -25) > "$OUT/opencl_backend.log"
  tail -25 "$OUT/opencl_backend.log"
  return $rc
}

run_bench() {
  local d=(--device reference --device auto)
  $tr bench "${d[@]}" --n 1e3,1e4,1e5,1e6 --time 2 --no-search 2>&1 | tee "$OUT/bench_nosearch.txt"
  $tr bench "${d[@]}" --n 1e3,1e4,1e5 --time 2 --no-kernels 2>&1 | tee "$OUT/bench_search.txt"
}

run_e2e() {
  local w=$b/e2e; mkdir -p $w
  $tr make torus 2 3 --n 2400 -o $w/s2400.vect
  local limit=${E2E_LIMIT:-520}
  # opencl: coarse levels below 2048 vertices on the reference (the default,
  # --device-from); opencl-all: every level on the GPU
  for d in opencl opencl-all reference; do
    local dev=(--device "${d%-all}")
    [ "$d" = opencl-all ] && dev+=(--device-from 0)
    ( $tr tighten $w/s2400.vect --n 150 --refine-to 2400 \
        -o $w/e2e.$d.vect --time-limit "$limit" --target 32.7435 "${dev[@]}" --json \
        > "$OUT/e2e.$d.json" 2> "$OUT/e2e.$d.err" ) &
  done
  wait
  for d in opencl opencl-all reference; do
    echo "== $d"; cat "$OUT/e2e.$d.json"; tail -2 "$OUT/e2e.$d.err"
    $tr measure $w/e2e.$d.vect
  done
}

rc=0
for p in "${phases[@]}"; do
  echo "=== $p ($(date -u +%T))"
  case $p in
    setup) setup || exit 1 ;;
    test) loader_path; run_tests || rc=1 ;;
    bench) loader_path; run_bench || rc=1 ;;
    e2e) loader_path; run_e2e || rc=1 ;;
    *) echo "unknown phase $p"; exit 2 ;;
  esac
done
exit $rc
