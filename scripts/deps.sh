#!/usr/bin/env bash
# Installs what Tightrope needs on Debian 12 if it is missing (non-interactive).
#   scripts/deps.sh [MORE-PACKAGES...]   (scripts/test.sh --oclgrind adds oclgrind)
set -euo pipefail
# parallel: GNU parallel, which runs the parts of a tightrope batch at once (docs/usage.md) and
# which its test runs for real
# libopenblas0-serial: CHOLMOD's dense kernels (the second-order solver's and the KKT
# certificate's factorisations) through OpenBLAS instead of the reference BLAS; one thread,
# so the two cores stay the tests' (bench/notes/2026-11-25-converged-last-digits.md)
# python3-venv: pip install ./python into a venv (scripts/test.sh --python); python3-numpy,
# python3-pytest: the Python package's tests against the build's library (ctest -L python)
# chromium-headless-shell, xz-utils: the gallery's test opens the release page in a real
# headless browser and unpacks its curves (scripts/gallery.py, tests/scripts/gallery_cli.sh)
pkgs=(build-essential cmake pkg-config ocl-icd-opencl-dev opencl-headers pocl-opencl-icd clinfo
      clang libclang-rt-14-dev gnuplot-nox libsuitesparse-dev libopenblas0-serial parallel
      python3-venv python3-numpy python3-pytest chromium-headless-shell xz-utils "$@")
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
