#!/usr/bin/env bash
# Times 'tightrope measure' on a smooth torus knot T(2,3) at N = 10^4, 10^5, 10^6.
#   bench/measure_bench.sh [BUILD_DIR] [N...]
# The knot: (1 + 0.45 cos 3t)(cos 2t, sin 2t) + 0.45 sin 3t z, t = 2 pi i / N,
# written as TSV with %.17g by awk (independent of 'tightrope make'). Each N
# is measured once untimed (file cache), then 3 times; the minimum and median
# wall time are printed, with the measured ropelength as a sanity check.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10000 100000 1000000)
tr="$build/tightrope"
[ -x "$tr" ] || { echo "no $tr: build first" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf "%-9s %-10s %-10s %s\n" N min_s median_s ropelength
for n in "${sizes[@]}"; do
  f="$work/torus_$n.tsv"
  awk -v n="$n" 'BEGIN { pi = atan2(0, -1);
    for (i = 0; i < n; i++) { t = 2 * pi * i / n; r = 1 + 0.45 * cos(3 * t);
      printf "%.17g %.17g %.17g\n", r * cos(2 * t), r * sin(2 * t), 0.45 * sin(3 * t) } }' > "$f"
  "$tr" measure "$f" --json > "$work/out.json"
  times=()
  for k in 1 2 3; do
    s=$(date +%s.%N)
    "$tr" measure "$f" --json > "$work/out.json"
    e=$(date +%s.%N)
    times+=("$(echo "$e - $s" | bc -l)")
  done
  sorted=($(printf "%s\n" "${times[@]}" | sort -g))
  rl=$(sed -n 's/.*"ropelength": \([^,]*\),.*/\1/p' "$work/out.json" | head -1)
  printf "%-9s %-10.3f %-10.3f %s\n" "$n" "${sorted[0]}" "${sorted[1]}" "$rl"
done
