#!/usr/bin/env bash
# A tightening whose result is longer than its start says so (tighten.c): a valid rope, but not
# what a tightening promises. A trefoil tightened at N 96 (3000 steps), then resampled along a
# spline to 800 and given one step, comes back longer than the 96-gon (the spline's overshoot
# is not undone in one step). Checked against `tightrope measure` of both files: the warning is
# on stderr exactly when the written result is the longer, and names both ropelengths; the
# first run (shorter than its start) and a circle (a result as long as its start) say nothing.
# Usage: longer_than_start_cli.sh TIGHTROPE WORK_DIR. Exit 0 pass, 1 fail.
set -u
tr=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
"$tr" make torus 2 3 --n 96 -o "$work/a.vect" >/dev/null || fail "make"
"$tr" tighten "$work/a.vect" -o "$work/b.vect" --n 96 --steps 3000 --no-kkt --device reference \
  >/dev/null 2>"$work/b.err" || fail "tighten at 96: $(cat "$work/b.err")"
grep -q "longer than the start" "$work/b.err" && fail "a warning for a run that shortened its start: $(cat "$work/b.err")"
"$tr" make circle -o "$work/o.vect" >/dev/null || fail "make circle"
"$tr" tighten "$work/o.vect" -o "$work/p.vect" --steps 5 --device reference >/dev/null 2>"$work/p.err" ||
  fail "tighten a circle: $(cat "$work/p.err")"
grep -q "longer than the start" "$work/p.err" && fail "a warning for a circle: $(cat "$work/p.err")"
"$tr" tighten "$work/b.vect" -o "$work/c.vect" --n 800 --steps 1 --no-kkt --device reference \
  >/dev/null 2>"$work/c.err" || fail "tighten at 800: $(cat "$work/c.err")"
cat "$work/c.err"
rl() { "$tr" measure "$1" | awk '$1 == "curve" { print $7 }'; }
start=$(rl "$work/b.vect") result=$(rl "$work/c.vect")
longer=$(awk -v a="$result" -v b="$start" 'BEGIN { print (a > b) ? 1 : 0 }')
if [ "$longer" = 1 ]; then
  said=$(sed -n 's/.*warning: the result (ropelength [0-9.]*) is longer than the start (\([0-9.]*\)).*/\1/p' "$work/c.err")
  [ -n "$said" ] && awk -v a="$said" -v b="$start" 'BEGIN { exit !(a - b < 1e-5 && b - a < 1e-5) }' ||
    fail "result $result longer than start $start, and no warning"
else
  # the premise of this test no longer holds: the one step brought it back below its start
  grep -q "is longer than the start" "$work/c.err" && fail "a warning for a result $result not longer than $start"
  fail "the premise: one step at 800 left the trefoil at $result, not longer than its start $start"
fi
echo "PASS: result $result, start $start, warned"
