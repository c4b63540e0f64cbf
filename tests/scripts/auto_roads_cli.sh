#!/usr/bin/env bash
# The automatic roads (issue 47 item 3): a loose start with --time-limit T >= 50 and no road
# flags is scouted (the start, then shuffled roads) in half of T, and the shortest scout is
# refined to 48 vertices per unit of its ropelength. Checked: the roads chosen and said on
# stderr, the written N against the shortest scout's ropelength, and the written trefoil
# shorter than that scout (how far below KnotInfo's 32.7436 it ends depends on the CPU the
# refinement gets: bench/plain_knots.sh measures that). With --tries (or a T under 50 s) one
# road, as before. T is 80 s: with 50 the refinement's 25 s were once not enough on a loaded
# 2-core machine (the CI's two test jobs and a solve beside them: N 1576 written at 33.89, the
# scout's 32.84, 2026-11-29), the same check.
# Usage: auto_roads_cli.sh TIGHTROPE WORK_DIR. Exit 0 pass, 1 fail.
set -u
tr=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
"$tr" make torus 2 3 --n 400 -o "$work/s.vect" >/dev/null || fail "make"
"$tr" tighten "$work/s.vect" -o "$work/a.vect" --time-limit 80 --no-kkt --device reference \
  >"$work/a.out" 2>"$work/a.err" || fail "tighten: $(cat "$work/a.err")"
cat "$work/a.err"
grep -q '^tightrope tighten: the automatic roads for a time limit of 80 s: up to 2 scouts' "$work/a.err" ||
  fail "no automatic roads said"
# road 2 is shuffled, unless road 1 spent the scouts' share (a loaded machine)
grep -q '^tightrope tighten: road 2 of 2: the start shuffled' "$work/a.err" ||
  grep -q "^tightrope tighten: the scouts' share of the time is spent after 1 of 2 roads" "$work/a.err" ||
  fail "road 2 is neither shuffled nor cut by the scouts' share"
grep -q "^tightrope tighten: road 1 of 2: the start compacted" "$work/a.err" || fail "road 1 is not the start compacted"
best=$(awk '/road [0-9]+ of 2: ropelength/ { if (m == "" || $NF < m) m = $NF } END { print m }' "$work/a.err")
# a scout climbs levels from its shuffled or compacted rope's 96 vertices (roads.c,
# SCOUT_LEVELS): the one refined has more (under a sanitizer its time may end at 96)
scout_n=$(sed -n 's/^tightrope tighten: the shortest scout (road [12], N \([0-9]*\)).*/\1/p' "$work/a.err")
[ -n "$scout_n" ] || fail "no scout refined"
if [ -z "${ASAN_OPTIONS:-}" ]; then
  [ "$scout_n" -gt 96 ] || fail "the scout stayed at N $scout_n: no level climbed"
fi
[ -n "$best" ] || fail "no scout finished"
want=$(awk -v b="$best" 'BEGIN { printf "%d", b * 48 + 0.5 }')
grep -Eq "^tightrope tighten: the shortest scout \(road [12], N [0-9]*\) (refined|resampled) to $want vertices$" "$work/a.err" ||
  fail "not refined to 48 x $best = $want vertices"
read -r n rl < <("$tr" measure "$work/a.vect" | awk '$1 == "curve" { print $2, $7 }')
# under a sanitizer (ten times slower) the refinement may not reach its N in the time
if [ -z "${ASAN_OPTIONS:-}" ]; then
  [ "$n" = "$want" ] || fail "wrote N $n, want $want"
  awk -v r="$rl" -v b="$best" 'BEGIN { exit !(r < b) }' || fail "ropelength $rl, not below the shortest scout's $best"
fi
# the scouts write no checkpoint (it would carry a scout's goals, and --resume would go on as
# that scout, never refined); a run stopped while scouting leaves none
"$tr" tighten "$work/s.vect" -o "$work/k.vect" --time-limit 50 --checkpoint "$work/k.ckpt" --checkpoint-every 0.2 \
  --no-kkt --device reference >/dev/null 2>"$work/k.err" &
pid=$!
sleep 3
kill -INT $pid
wait $pid
grep -q "^tightrope tighten: the shortest scout" "$work/k.err" && fail "the refinement began within 3 s: nothing tested"
grep -q "^tightrope tighten: no checkpoint: the run was interrupted while its scouts ran" "$work/k.err" ||
  fail "no note that the scouts wrote no checkpoint: $(cat "$work/k.err")"
[ -e "$work/k.ckpt" ] && fail "a scout wrote a checkpoint: $(grep -a goals "$work/k.ckpt")"
# a road flag, or a T under 50 s: one road
# (the start's N is then the run's goal: the steps and the time cut here
# stop it short, exit 1, its best written)
"$tr" tighten "$work/s.vect" -o "$work/b.vect" --time-limit 50 --tries 1 --steps 300 --no-kkt --device reference \
  >/dev/null 2>"$work/b.err"
rc=$?
reached_or_said() { # exit 0 at N 400, or exit 1 saying it stopped short of the start's N
  case $1 in
  0) "$tr" measure "$2" | awk '$1 == "curve" { exit !($2 == 400) }' ;;
  1) [ -s "$2" ] && grep -q "before reaching the start's N 400; wrote" "$3" ;;
  *) false ;;
  esac
}
reached_or_said $rc "$work/b.vect" "$work/b.err" || fail "tighten --tries 1 (exit $rc): $(cat "$work/b.err")"
grep -q 'automatic roads' "$work/b.err" && fail "--tries 1 took the automatic roads"
"$tr" tighten "$work/s.vect" -o "$work/c.vect" --time-limit 10 --no-kkt --device reference \
  >/dev/null 2>"$work/c.err"
rc=$?
reached_or_said $rc "$work/c.vect" "$work/c.err" || fail "tighten T = 10 (exit $rc): $(cat "$work/c.err")"
grep -q 'automatic roads' "$work/c.err" && fail "T = 10 took the automatic roads"
# --shuffles alone is refused: which roads it names needs --tries
"$tr" tighten "$work/s.vect" -o "$work/d.vect" --shuffles 2 2>"$work/d.err" && fail "--shuffles without --tries accepted"
grep -q 'needs --tries' "$work/d.err" || fail "no message: $(cat "$work/d.err")"
exit 0
