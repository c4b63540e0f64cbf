#!/usr/bin/env bash
# The second-order solver's route through tighten --newton (issue 26).
# Usage: newton_route.sh CASE TIGHTROPE SOURCE_DIR WORK_DIR. Exit 0 pass, 1 fail.
set -u
case_=$1 tr=$2 src=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
# ropelength FILE: the oracle's, for a one-component curve
ropelength() { "$tr" measure "$1" | awk '$1 == "curve" { print $7 }'; }
case $case_ in
refine)
  # A tightened N = 72 trefoil resampled to 144 by --n goes to the solver,
  # which must end shorter than the coarse knot (a finer polygon of the same
  # knot has more room) and above 31.32 (no knot is shorter: Denne et al.).
  "$tr" make torus 2 3 --n 72 -o "$work/s.vect" >/dev/null || fail "make"
  "$tr" tighten "$work/s.vect" -o "$work/a.vect" --newton --time-limit 3 --quiet --device reference 2>"$work/a.err" ||
    fail "coarse tighten: $(cat "$work/a.err")"
  "$tr" tighten "$work/a.vect" --n 144 -o "$work/b.vect" --newton --time-limit 10 --quiet --device reference \
    2>"$work/b.err" || fail "refined tighten: $(cat "$work/b.err")"
  grep -q '^# newton accepted' "$work/b.vect" || fail "no 'newton accepted' line in the refined output"
  a=$(ropelength "$work/a.vect") b=$(ropelength "$work/b.vect")
  echo "N = 72: $a, N = 144: $b"
  awk -v a="$a" -v b="$b" 'BEGIN { exit !(b < a && b > 31.32) }' || fail "refined $b not in (31.32, $a)"
  ;;
sigint)
  # SIGINT while the solver runs on a tight start (the N = 2400 trefoil
  # resampled to 4800: the solver needs ~10 s there) stops the run within a
  # second or so, with exit 1 and a curve written that measures.
  start=$(date +%s%N)
  "$tr" tighten "$src/bench/data/trefoil_2400.vect" --n 4800 --newton -o "$work/o.vect" --quiet --device reference \
    2>"$work/err" &
  pid=$!
  sleep 2
  kill -INT $pid
  wait $pid
  rc=$?
  took=$(awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN { printf "%.2f", (b - a) / 1e9 }')
  echo "exit $rc after $took s"
  [ "$rc" = 1 ] || fail "exit $rc, want 1: $(cat "$work/err")"
  grep -q 'interrupted; wrote' "$work/err" || fail "no 'interrupted' line: $(cat "$work/err")"
  # the signal comes 2 s in; the solver polls it every step and the warm
  # start every iteration, the strut list's build (~0.3 s here, several
  # seconds under the sanitizers) not at all
  limit=6; [ -n "${ASAN_OPTIONS:-}" ] && limit=20
  awk -v t="$took" -v l="$limit" 'BEGIN { exit !(t < l) }' || fail "took $took s to stop (limit $limit)"
  r=$(ropelength "$work/o.vect")
  [ -n "$r" ] || fail "the written curve does not measure"
  ;;
auto)
  # Without route flags a loose start of N >= 200 is tightened from N / 4
  # and refined back to N (said on stderr); a tight one is left at its N.
  "$tr" make torus 2 3 --n 240 -o "$work/s.vect" >/dev/null || fail "make"
  "$tr" tighten "$work/s.vect" -o "$work/t.vect" --time-limit 3 --no-kkt --device reference 2>"$work/err" >/dev/null ||
    fail "tighten: $(cat "$work/err")"
  grep -q 'is loose .* tightening from 64 vertices and refining to 240' "$work/err" || fail "no route note: $(cat "$work/err")"
  "$tr" measure "$work/t.vect" | awk '$1 == "curve" { exit !($2 == 240) }' || fail "the output is not at N = 240"
  "$tr" tighten "$src/bench/data/trefoil_1600.vect" -o "$work/u.vect" --steps 1 --no-kkt --device reference \
    2>"$work/err2" >/dev/null || fail "tight start: $(cat "$work/err2")"
  grep -q 'is loose' "$work/err2" && fail "a tight start was called loose"
  # the start's N is that route's goal, as a given --refine-to is: a run
  # that stops short of it (here after 5 steps at N 64) writes its best
  # and exits 1, saying so (it exited 0 with a 64-gon for a 240-gon)
  "$tr" tighten "$work/s.vect" -o "$work/v.vect" --steps 5 --no-kkt --device reference 2>"$work/err3" >/dev/null
  rc=$?
  [ $rc = 1 ] || fail "stopped short of the start's N: exit $rc, not 1: $(cat "$work/err3")"
  grep -q "stopped (steps) at N 64 before reaching the start's N 240; wrote" "$work/err3" ||
    fail "no message: $(cat "$work/err3")"
  "$tr" measure "$work/v.vect" | awk '$1 == "curve" { exit !($2 == 64) }' || fail "the coarse level was not written"
  ;;
*) fail "unknown case $case_" ;;
esac
exit 0
