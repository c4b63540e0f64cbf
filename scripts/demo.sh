#!/usr/bin/env bash
# Installs missing packages, builds, and runs the demo: tighten a trefoil from
# a torus-knot start and print its certified ropelength.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc)"
mkdir -p demo
./build/tightrope make torus 2 3 --n 120 -o demo/trefoil-start.vect
./build/tightrope measure demo/trefoil-start.vect
