#!/usr/bin/env bash
# Installs missing packages, builds, and runs the demo: tighten a trefoil from
# a torus-knot start, then measure the written file independently and print
# its certified ropelength (the ideal trefoil is 32.7429...).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc)"
mkdir -p demo
# T(2,3) at N = 400, tightened at N = 100, 200, 400 (each level polished) in 20 s
./build/tightrope make torus 2 3 --n 400 -o demo/trefoil-start.vect
./build/tightrope tighten demo/trefoil-start.vect -o demo/trefoil.vect --n 100 --refine-to 400 --time-limit 20
./build/tightrope measure --kkt demo/trefoil.vect
