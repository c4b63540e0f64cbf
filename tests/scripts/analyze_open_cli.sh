#!/usr/bin/env bash
# CLI checks of 'tightrope analyze' on open ropes (issue 23).
# Usage: analyze_open_cli.sh CASE TIGHTROPE WORK_DIR. Exit 0 pass, 1 fail.
set -u
case_=$1 tr=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
# helix N TURNS HAND: the open helix r = 0.2, c = HAND * 0.4 (pitch 0.8 pi), VECT
helix() {
  awk -v n="$1" -v turns="$2" -v h="$3" 'BEGIN {
    pi = atan2(0, -1); r = 0.2; c = h * 0.4
    printf "VECT\n1 %d 0\n%d\n0\n", n, n
    for (i = 0; i < n; i++) { t = 2 * pi * turns * i / (n - 1); printf "%.17g %.17g %.17g\n", r * cos(t), r * sin(t), c * t }
  }'
}
# maxerr CSV COLUMN WANT LMIN LMAX: the largest |value - WANT| over rows with l in [LMIN, LMAX]
maxerr() {
  awk -F, -v col="$2" -v want="$3" -v lo="$4" -v hi="$5" '
    /^#/ || $1 !~ /^[0-9]+$/ { next }
    $2 >= lo && $2 <= hi { d = $col - want; if (d < 0) d = -d; if (d > m) m = d; rows++ }
    END { if (!rows) print "none"; else printf "%.3g\n", m }' "$1"
}
case $case_ in
helix)
  # kappa = r/(r^2+c^2) = 1 and tau = c/(r^2+c^2) = +-2 to 1e-3, away from the
  # ends (l in [0.5, L - 0.5]); --no-scale keeps the geometry (its thickness is
  # the curvature radius 1 only up to the polygon's O(e^2)).
  for hand in 1 -1; do
    helix 2000 3 "$hand" >"$work/helix$hand.vect"
    "$tr" analyze "$work/helix$hand.vect" --out "$work/out$hand" --no-scale >"$work/stdout" 2>"$work/stderr" ||
      fail "exit $?: $(cat "$work/stderr")"
    for f in curvature.csv torsion.csv summary.json report.txt; do
      [ -s "$work/out$hand/$f" ] || fail "missing $f"
    done
    [ "$(grep -vc '^#' "$work/out$hand/curvature.csv")" = 1999 ] || fail "curvature.csv: one row per interior vertex"
    grep -q '"open": true' "$work/out$hand/summary.json" || fail "summary.json does not say open"
    L=$(awk 'BEGIN { print 6 * atan2(0, -1) * sqrt(0.2) }')
    ke=$(maxerr "$work/out$hand/curvature.csv" 3 1 0.5 "$(awk -v L="$L" 'BEGIN { print L - 0.5 }')")
    te=$(maxerr "$work/out$hand/torsion.csv" 4 "$((2 * hand))" 0.5 "$(awk -v L="$L" 'BEGIN { print L - 0.5 }')")
    echo "hand $hand: max |kappa - 1| = $ke, max |tau - $((2 * hand))| = $te"
    awk -v k="$ke" -v t="$te" 'BEGIN { exit !(k != "none" && t != "none" && k + 0 < 1e-3 && t + 0 < 1e-3) }' ||
      fail "hand $hand: kappa error $ke, tau error $te"
  done
  ;;
clasp)
  # the clasp from 'make clasp': two open ropes, one directory each
  "$tr" make clasp -o "$work/clasp.vect" >/dev/null || fail "make clasp"
  "$tr" analyze "$work/clasp.vect" --out "$work/out" >"$work/stdout" 2>"$work/stderr" || fail "exit $?: $(cat "$work/stderr")"
  for k in 0 1; do
    for f in curvature.csv torsion.csv summary.json report.txt; do
      [ -s "$work/out/comp$k/$f" ] || fail "missing comp$k/$f"
    done
  done
  grep -q 'open rope' "$work/stdout" || fail "report"
  ;;
short)
  # an open rope of 3 vertices: one line naming the file, exit 2, nothing written
  printf 'VECT\n1 3 0\n3\n0\n0 0 0\n1 0 0\n1 1 0\n' >"$work/short.vect"
  "$tr" analyze "$work/short.vect" --out "$work/out" 2>"$work/stderr"
  [ $? = 2 ] || fail "exit status"
  [ "$(wc -l <"$work/stderr")" = 1 ] && grep -q short.vect "$work/stderr" || fail "message: $(cat "$work/stderr")"
  [ -e "$work/out" ] && fail "output written"
  ;;
mesh)
  # --mesh: a regular 100-gon of radius 4 (as given): every ring vertex at
  # distance 1 from the circle (the bisector planes contain the axis), every
  # edge in exactly two triangles, the header's counts those of the body
  awk 'BEGIN { pi = atan2(0, -1); printf "VECT\n1 100 0\n-100\n0\n"
    for (i = 0; i < 100; i++) printf "%.17g %.17g 0\n", 4 * cos(2 * pi * i / 100), 4 * sin(2 * pi * i / 100) }' >"$work/circle.vect"
  "$tr" analyze "$work/circle.vect" --out "$work/out" --no-scale --mesh "$work/circle.ply" --mesh-sides 12 \
    >"$work/stdout" 2>"$work/stderr" || fail "exit $?: $(cat "$work/stderr")"
  grep -q "^mesh: $work/circle.ply (1200 vertices, 2400 triangles)" "$work/stdout" || fail "stdout: $(cat "$work/stdout")"
  ls "$work"/.*.tmp* "$work"/*.tmp* >/dev/null 2>&1 && fail "temporary left behind"
  awk -v R=4 '
    NR == 1 && $0 != "ply" { print "not PLY"; bad = 1; exit }
    /^element vertex / { nv = $3 } /^element face / { nf = $3 }
    !body { if ($0 == "end_header") body = 1; next }
    vi < nv { d = sqrt((sqrt($1 * $1 + $2 * $2) - R) ^ 2 + $3 * $3) - 1; if (d < 0) d = -d; if (d > dmax) dmax = d; vi++; next }
    { if ($1 != 3) { print "not a triangle: " $0; bad = 1 }
      for (k = 2; k <= 4; k++) { a = $k; b = $(k == 4 ? 2 : k + 1); e[a < b ? a " " b : b " " a]++ }
      fi++ }
    END { if (bad) exit 1
      if (vi != nv || fi != nf || nv != 1200 || nf != 2400) { print "counts " vi " " nv " " fi " " nf; exit 1 }
      if (dmax > 1e-9) { print "distance off by " dmax; exit 1 }
      for (k in e) if (e[k] != 2) { print "edge " k " in " e[k] " triangles"; exit 1 } }' "$work/circle.ply" ||
    fail "circle.ply"
  # the clasp's two ropes, capped: (100 x 16 + 2) vertices each
  "$tr" make clasp -o "$work/clasp.vect" >/dev/null || fail "make clasp"
  "$tr" analyze "$work/clasp.vect" --out "$work/clasp" --mesh "$work/clasp.ply" >"$work/stdout" 2>"$work/stderr" ||
    fail "clasp: exit $?: $(cat "$work/stderr")"
  grep -q '^element vertex 3204$' "$work/clasp.ply" && grep -q '^element face 6400$' "$work/clasp.ply" || fail "clasp.ply counts"
  # refused in one line naming the file, nothing written
  "$tr" analyze "$work/circle.vect" --out "$work/o2" --mesh "$work/no/such/dir/x.ply" 2>"$work/stderr"
  [ $? = 2 ] || fail "unwritable mesh: exit status"
  [ "$(wc -l <"$work/stderr")" = 1 ] && grep -q "no/such/dir/x.ply" "$work/stderr" || fail "message: $(cat "$work/stderr")"
  [ -e "$work/o2" ] && fail "output written for an unwritable mesh"
  ;;
*) fail "unknown case $case_" ;;
esac
exit 0
