#!/usr/bin/env bash
# The KKT certificate of a link of many small components (issue 45):
#   bench/kkt_components.sh [TIGHTROPE] [COUNT ...]   (default build/tightrope; 200 500 1000 2000)
# COUNT regular octagons of circumradius 1, 10 apart on a grid, measured with
# `tightrope measure --kkt`; prints the count, the wall time, the peak memory
# and the certificate's line. The union is critical (residual ~1e-15): each
# octagon's thickness cos(pi/8) is its MinRad and half its opposite edges'
# distance.
#
# Measured on the 2-core VM under load (RelWithDebInfo), before and after the
# dense columns of small components went into the sparse factor
# (oracle/rowchol.c):
#   count   a56bc33           now
#     200   0.25 s   20 MB    0.02 s  12 MB
#     500   3.0 s    73 MB
#    1000  19.2 s   257 MB    0.09 s  32 MB
#    2000  killed at 300 s, 955 MB   0.25 s  58 MB
# The cost was the Woodbury update's: one dense column per component (nr x nu
# numbers), the nu^2 nr products of I + U^T K^-1 U and its nu^3 Cholesky. A
# generous bound for a check by hand: 2000 components well under 10 s.
set -eu
tr=${1:-build/tightrope}
[ $# -gt 0 ] && shift
counts=${*:-200 500 1000 2000}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for m in $counts; do
  awk -v m="$m" 'BEGIN { n = 8; pi = atan2(0, -1); g = int(sqrt(m)) + 1; print "VECT"; printf "%d %d 0\n", m, m * n
    for (k = 0; k < m; k++) printf "%d ", -n; print ""; for (k = 0; k < m; k++) printf "0 "; print ""
    for (k = 0; k < m; k++) for (i = 0; i < n; i++) { t = 2 * pi * i / n
      printf "%.17g %.17g 0\n", 10 * (k % g) + cos(t), 10 * int(k / g) + sin(t) } }' >"$dir/rings.vect"
  /usr/bin/time -f "%e s %M KB" -o "$dir/time" "$tr" measure --kkt "$dir/rings.vect" >"$dir/out"
  printf '%6d  %s  %s\n' "$m" "$(cat "$dir/time")" "$(grep 'KKT residual' "$dir/out")"
done
