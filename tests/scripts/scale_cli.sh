#!/usr/bin/env bash
# tighten --scale (issue 24: every start works with one command).
# Usage: scale_cli.sh CASE TIGHTROPE WORK_DIR. Exit 0 pass, 1 fail.
#   clasp:  the made clasp (thickness t, planes z = +-5), doubled in
#           coordinates and plane offsets, comes back at thickness 1 with its
#           planes at z = +-5 / t and its ends on them;
#   coarse: a 30-vertex trefoil with edges of 1.26 at thickness 1 (the engine
#           takes < 1) is resampled along a spline, not refused.
set -u
case_=$1 tr=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
if [ "$case_" = coarse ]; then
  awk 'BEGIN { n = 30; pi = atan2(0, -1); printf "VECT\n1 %d 0\n-%d\n0\n", n, n
    for (i = 0; i < n; i++) { t = 2 * pi * i / n; r = 2 + cos(3 * t)
      printf "%.17g %.17g %.17g\n", r * cos(2 * t), r * sin(2 * t), sin(3 * t) } }' > "$work/s.vect"
  "$tr" tighten "$work/s.vect" -o "$work/t.vect" --scale --steps 1 --quiet --no-kkt --device reference 2>"$work/err" ||
    fail "tighten --scale: $(cat "$work/err")"
  grep -q 'too coarse for thickness 1; resampled along a spline to [0-9]* vertices' "$work/err" || fail "no note: $(cat "$work/err")"
  # the written curve: more vertices, edges below 1 at thickness 1
  "$tr" measure "$work/t.vect" | awk '$1 == "curve" { if (!($2 > 30 && $3 / $2 / $6 < 1)) exit 1; ok = 1 } END { exit !ok }' ||
    fail "written: $("$tr" measure "$work/t.vect" | tail -1)"
  exit 0
fi
[ "$case_" = clasp ] || fail "unknown case $case_"
"$tr" make clasp -o "$work/c.vect" >/dev/null || fail "make clasp"
# VECT: the header's four lines (VECT, counts, vertex counts, colours), then coordinates
awk -v CONVFMT=%.17g -v OFMT=%.17g '/^# Constraint/ { $8 = 2 * $8; print; next }
     !/^#/ && ++n > 4 && NF >= 3 { $1 = 2 * $1; $2 = 2 * $2; $3 = 2 * $3 } { print }' \
  "$work/c.vect" > "$work/c2.vect"
grep -q '^# Constraint 1 Plane 0 0 1 10$' "$work/c2.vect" || fail "the doubled file's plane: $(grep Constraint "$work/c2.vect")"
"$tr" tighten "$work/c2.vect" -o "$work/t.vect" --scale --steps 1 --quiet --no-kkt --device reference 2>"$work/err" ||
  fail "tighten --scale: $(cat "$work/err")"
# the planes z = 10 and -10 of the doubled file scaled by 1 / (2 t), t the
# made clasp's thickness: z = +-5 / t; every end vertex ('# Cst:') on its plane
t=$("$tr" measure "$work/c.vect" | awk '$1 == "curve" { print $6 }')
awk -v t="$t" '
  /^# Constraint/ { z[$3] = $8; want = ($3 == 1 ? 5 : -5) / t; if (($8 - want)^2 > 1e-20 * want^2) bad = bad " plane " $3 "=" $8 " want " want }
  /# Cst:/ { id = $NF; d = $3 - z[id]; if (d * d > 1e-24 * z[id] * z[id]) bad = bad " end off its plane " id ": " $3 }
  END { if (bad != "") { print bad; exit 1 } }' "$work/t.vect" || fail "after --scale:$(awk '/^# Constraint/' "$work/t.vect")"
exit 0
