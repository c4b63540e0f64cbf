#!/usr/bin/env bash
# Everything the OpenCL figures of bench/RESULTS.md need on a machine with a GPU,
# in as few calls as a short lease allows:
#   bench/gpu_session.sh PHASE... [-- OUTDIR]
# PHASE: pack  (HERE, on the Debian 12 build machine, before the lease: fills .gpu/
#               with what the GPU image lacks and cannot fetch (it has no network):
#               OpenCL headers and loader, SuiteSparse's CHOLMOD with the libraries
#               it needs, and the reference data ../shared/data; carry ".gpu")
#        setup (find the vendor's OpenCL, build in build-gpu), test (ctest),
#        bench (tightrope bench with and without the neighbour search),
#        e2e   (N = 2400 trefoil to 32.7435 on the GPU with the coarse levels on the
#               reference, and on the reference, side by side; then on the GPU at
#               every level, alone),
#        all   (setup test bench e2e).
# Everything printed also goes to OUTDIR/session.log; OUTDIR is $OUT where the
# lending tool sets it, else /tmp/gpu-out.
set -uo pipefail
cd "$(dirname "$0")/.."
phases=()
while [ $# -gt 0 ]; do
  case $1 in
    --) OUT=${2:?"an output folder after --"}; shift 2 ;;
    all) phases+=(setup test bench e2e); shift ;;
    *) phases+=("$1"); shift ;;
  esac
done
[ ${#phases[@]} -gt 0 ] || { echo "usage: bench/gpu_session.sh PHASE... [-- OUTDIR] (PHASE: pack setup test bench e2e all)" >&2; exit 2; }
OUT=${OUT:-/tmp/gpu-out}
mkdir -p "$OUT"
exec > >(tee -a "$OUT/session.log") 2>&1
b=build-gpu
tr=$b/tightrope

# Copies, from this machine, what the build and the tests need and the GPU
# image lacks. Libraries are those CHOLMOD loads, less the C runtime; setup
# uses a copy only where the GPU machine has no library of that name.
pack() {
  local h=/usr/include/suitesparse/cholmod.h lib=/usr/lib/x86_64-linux-gnu
  [ -f $h ] && [ -f /usr/include/CL/cl.h ] && [ -f $lib/libOpenCL.so.1 ] \
    || { echo "pack: needs libsuitesparse-dev, opencl-headers and ocl-icd-opencl-dev here (scripts/deps.sh)"; return 1; }
  rm -rf .gpu && mkdir -p .gpu/include .gpu/lib .gpu/cholmod
  cp -r /usr/include/CL /usr/include/suitesparse .gpu/include/
  cp -L $lib/libOpenCL.so.1 .gpu/lib/
  cp -L $lib/libcholmod.so.3 .gpu/cholmod/
  ldd $lib/libcholmod.so.3 | awk '$3 ~ /^\// {print $3}' | while read -r so; do
    case $(basename "$so") in
      libc.so.*|libm.so.*|libgcc_s.so.*|ld-linux*) ;;
      *) cp -L "$so" .gpu/cholmod/ ;;
    esac
  done
  ln -s libcholmod.so.3 .gpu/cholmod/libcholmod.so
  if [ -d ../shared/data ]; then
    mkdir -p .gpu/shared && cp -r ../shared/data .gpu/shared/
  else
    echo "pack: no ../shared/data: the tests that compare with it will skip on the GPU machine"
  fi
  du -sh .gpu
  ls .gpu/cholmod
}

setup() {
  nvidia-smi -L || true
  # the reference data beside the checkout (../shared) does not travel: a copy may be carried in .gpu/
  local shared=../shared
  [ -d $shared/data ] || shared=.gpu/shared
  [ -d $shared/data ] || echo "warning: no reference data (../shared/data or .gpu/shared/data): those tests skip"
  echo "cores: $(nproc)"; gcc --version | head -1; cmake --version | head -1
  # The driver ships the ICD (libnvidia-opencl); containers often lack the
  # /etc/OpenCL/vendors entry that lets a loader find it.
  local icd=
  icd=$(ldconfig -p | awk '/libnvidia-opencl\.so\.1/ {print $NF; exit}')
  [ -n "$icd" ] || icd=$(find / -xdev -name 'libnvidia-opencl.so*' 2>/dev/null | head -1)
  echo "vendor ICD: ${icd:-none}"
  ls /etc/OpenCL/vendors 2>/dev/null
  if [ -n "$icd" ] && ! grep -qs nvidia /etc/OpenCL/vendors/*.icd; then
    { mkdir -p /etc/OpenCL/vendors && echo "$icd" > /etc/OpenCL/vendors/nvidia.icd; } 2>/dev/null \
      || echo "warning: cannot write /etc/OpenCL/vendors/nvidia.icd (not root?): the loader may not find the GPU"
  fi
  # Headers and loader: the system's, else CUDA's, else the copies carried in .gpu/.
  local inc= lib=
  for d in /usr/include /usr/local/cuda/include .gpu/include; do
    [ -f "$d/CL/cl.h" ] && { inc=$(realpath "$d"); break; }
  done
  lib=$(ldconfig -p | awk '/libOpenCL\.so\.1 / {print $NF; exit}')
  [ -n "$lib" ] || lib=$(ls /usr/local/cuda/lib64/libOpenCL.so.1 /usr/local/cuda/targets/x86_64-linux/lib/libOpenCL.so.1 2>/dev/null | head -1)
  [ -n "$lib" ] || { [ -f .gpu/lib/libOpenCL.so.1 ] && lib=$(realpath .gpu/lib/libOpenCL.so.1); }
  if [ -z "$inc" ] || [ -z "$lib" ]; then
    echo "no OpenCL headers (${inc:-none}) or loader (${lib:-none}): install opencl-headers and ocl-icd-opencl-dev, or run 'bench/gpu_session.sh pack' on the build machine and carry .gpu"
    return 1
  fi
  echo "headers: $inc  loader: $lib"
  local libdirs=$(dirname "$lib")
  # CHOLMOD: the system's (libsuitesparse-dev), else the copy carried in .gpu/,
  # each of its libraries only where the system has none of that name.
  local cholmod=()
  if [ ! -f /usr/include/suitesparse/cholmod.h ] && [ ! -f /usr/include/cholmod.h ]; then
    [ -f .gpu/cholmod/libcholmod.so.3 ] \
      || { echo "no CHOLMOD: install libsuitesparse-dev, or run 'bench/gpu_session.sh pack' on the build machine and carry .gpu"; return 1; }
    local own=$b/cholmod-lib
    rm -rf $own && mkdir -p $own
    for so in .gpu/cholmod/*; do
      local n=$(basename "$so")
      ldconfig -p | grep -q "^[[:space:]]*$n " || ln -s "$(realpath "$so")" $own/$n
    done
    echo "CHOLMOD from .gpu/: $(ls $own | tr '\n' ' ')"
    libdirs=$libdirs:$(realpath $own)
    cholmod=(-DCHOLMOD_INCLUDE_DIR="$(realpath .gpu/include/suitesparse)"
             -DCHOLMOD_LIBRARY="$(realpath $own)/libcholmod.so")
  fi
  export LD_LIBRARY_PATH=$libdirs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  local sd=
  [ -d $shared/data ] && sd=$(realpath $shared)
  cmake -S . -B $b -DCMAKE_BUILD_TYPE=RelWithDebInfo ${sd:+-DTIGHTROPE_SHARED_DIR="$sd"} \
    -DOpenCL_INCLUDE_DIR="$inc" -DOpenCL_LIBRARY="$lib" "${cholmod[@]}" > "$OUT/cmake.log" 2>&1 \
    || { tail -20 "$OUT/cmake.log"; return 1; }
  cmake --build $b -j "$(nproc)" > "$OUT/build.log" 2>&1 || { tail -30 "$OUT/build.log"; return 1; }
  echo "$libdirs" > $b/library-path
  $tr devices
  $tr devices | grep -qi nvidia || { echo "no NVIDIA OpenCL device: the GPU figures cannot be taken"; return 1; }
}

library_path() {
  [ -f $b/library-path ] || { echo "no $b/library-path: run the setup phase first"; return 1; }
  export LD_LIBRARY_PATH=$(cat $b/library-path)${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
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
  local d=(--device reference --device nvidia) r=0
  $tr bench "${d[@]}" --n 1e3,1e4,1e5,1e6 --time 2 --no-search 2>&1 | tee "$OUT/bench_nosearch.txt" || r=1
  $tr bench "${d[@]}" --n 1e3,1e4,1e5 --time 2 --no-kernels 2>&1 | tee "$OUT/bench_search.txt" || r=1
  return $r
}

# One run to the target; its JSON and error lines land in $OUT, its curve in $OUT/e2e.
e2e_one() {
  local d=$1 w=$OUT/e2e limit=${E2E_LIMIT:-520}
  local dev=(--device "${d%-all}")
  [ "$d" = nvidia-all ] && dev+=(--device-from 0)
  $tr tighten $w/s2400.vect --n 150 --refine-to 2400 -o $w/e2e.$d.vect --time-limit "$limit" \
    --target 32.7435 "${dev[@]}" --json > "$OUT/e2e.$d.json" 2> "$OUT/e2e.$d.err"
}

run_e2e() {
  local w=$OUT/e2e r=0; mkdir -p $w
  $tr make torus 2 3 --n 2400 -o $w/s2400.vect || return 1
  # nvidia: coarse levels below 2048 vertices on the reference (the default,
  # --device-from), the last on the GPU; it and the reference share no more
  # than the 16-core host, so they run side by side. nvidia-all (every level
  # on the GPU) then runs alone.
  local pids=() d
  for d in nvidia reference; do e2e_one $d & pids+=($!); done
  for p in "${pids[@]}"; do wait "$p" || r=1; done
  e2e_one nvidia-all || r=1
  for d in nvidia reference nvidia-all; do
    echo "== $d"; cat "$OUT/e2e.$d.json"; tail -2 "$OUT/e2e.$d.err"
    grep -q '"stop": "target"' "$OUT/e2e.$d.json" || { echo "$d: did not reach 32.7435"; r=1; }
    $tr measure $w/e2e.$d.vect || r=1
  done
  return $r
}

rc=0
for p in "${phases[@]}"; do
  echo "=== $p ($(date -u +%T))"
  case $p in
    pack) pack || exit 1 ;;
    setup) setup || exit 1 ;;
    test) library_path && run_tests || rc=1 ;;
    bench) library_path && run_bench || rc=1 ;;
    e2e) library_path && run_e2e || rc=1 ;;
    *) echo "unknown phase $p"; exit 2 ;;
  esac
done
exit $rc
