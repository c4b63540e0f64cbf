#!/usr/bin/env bash
# CLI checks of 'tightrope analyze' on open ropes and the clasp's anatomy (issue 23).
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
  # a clasp not yet tightened has no anatomy, and says why
  grep -q '^clasp anatomy: not found: ' "$work/stdout" || fail "no anatomy line: $(cat "$work/stdout")"
  grep -q '"found": false, "why": ' "$work/out/comp0/summary.json" || fail "summary.json: no reason"
  [ -e "$work/out/comp0/pieces.csv" ] && fail "pieces.csv without an anatomy"
  ;;
clasp_tight)
  # 'make clasp' (100 vertices per rope) tightened by the serial reference,
  # its anatomy checked against the physics (docs/physics.md 6.2), not our
  # own numbers: the shoulder at curvature 1/2 and the kink at 1 (the pair
  # averages to 1e-3, REFERENCE.md 6.3); E, S, G, K in order on every half;
  # D1 and D2 (0.0078 and 0.0004 wide, Starostin) never called resolved at
  # an edge of 0.14; each rope symmetric about its tip and the ropes
  # congruent from the tip, to the uncertainties they state
  "$tr" make clasp --n 100 -o "$work/clasp.vect" >/dev/null || fail "make clasp"
  "$tr" tighten "$work/clasp.vect" -o "$work/tight.vect" --device reference --quiet >"$work/tighten.out" 2>&1 ||
    fail "tighten: $(cat "$work/tighten.out")"
  "$tr" analyze "$work/tight.vect" --out "$work/out" --plots >"$work/stdout" 2>"$work/stderr" ||
    fail "exit $?: $(cat "$work/stderr")"
  for k in 0 1; do
    d=$work/out/comp$k
    [ -s "$d/pieces.csv" ] || fail "comp$k: no pieces.csv: $(grep -A1 'clasp anatomy' "$work/stdout")"
    # the numbers after "key": in the clasp object's summary line
    val() { grep -o "\"$1\": {\"$2\": [-0-9.e+]*" "$d/summary.json" | head -1 | sed 's/.*: //'; }
    sh=$(val shoulder kappa) kk=$(val kink kappa)
    echo "comp$k: shoulder kappa $sh, kink kappa $kk"
    awk -v s="$sh" -v k="$kk" 'BEGIN { d = s - 0.5; e = k - 1; exit !(s != "" && k != "" && d * d < 1e-6 && e * e < 1e-6) }' ||
      fail "comp$k: shoulder $sh, kink $kk"
    awk -F, '
      /^#/ || $1 == "half" { next }
      { rows++; key = $1 " " $3; st[key] = $4; from[key] = $5; to[key] = $7; w[key] = $9 }
      END {
        if (rows != 12) { print "rows " rows; exit 1 }
        for (h = 0; h <= 1; h++) {
          if (st[h " D1"] == "resolved" || st[h " D2"] == "resolved") { print "half " h ": a deep resolved at e = 0.14"; exit 1 }
          n = split("E S G K", p, " ")
          for (i = 1; i <= n; i++) if (st[h " " p[i]] != "resolved" || !(w[h " " p[i]] > 0)) { print "half " h ": " p[i] " " st[h " " p[i]]; exit 1 }
          if (!(to[h " E"] <= from[h " S"] + 1e-12 && to[h " S"] <= from[h " G"] + 1e-12 && to[h " G"] <= from[h " K"] + 1e-12)) { print "half " h ": order"; exit 1 }
        } }' "$d/pieces.csv" || fail "comp$k: pieces.csv"
    for m in symmetry congruence; do
      diff=$(grep -o "\"$m\": {[^}]*" "$d/summary.json" | grep -o '"boundary_diff": [-0-9.e+]*' | sed 's/.*: //')
      derr=$(grep -o "\"$m\": {[^}]*" "$d/summary.json" | grep -o '"boundary_err": [-0-9.e+]*' | sed 's/.*: //')
      awk -v a="$diff" -v b="$derr" 'BEGIN { exit !(a != "" && b != "" && a + 0 <= b + 0) }' || fail "comp$k: $m $diff +- $derr"
    done
    if command -v gnuplot >/dev/null; then
      for f in clasp_curvature.png clasp_d1.png clasp_d2.png; do [ -s "$d/$f" ] || fail "comp$k: no $f"; done
    fi
  done
  grep -q '^  shoulder kappa 0.5' "$work/stdout" || fail "report: $(cat "$work/stdout")"
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
