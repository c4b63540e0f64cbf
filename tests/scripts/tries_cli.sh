#!/usr/bin/env bash
# tighten --tries K --seed S (issue 24 item 1): K roads, the shortest written.
# Usage: tries_cli.sh TIGHTROPE WORK_DIR. Exit 0 pass, 1 fail.
set -u
tr=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
"$tr" make torus 2 3 --n 72 -o "$work/s.vect" >/dev/null || fail "make"
# --steps, not a time limit, so that every road is the same computation twice
for run in a b; do
  "$tr" tighten "$work/s.vect" -o "$work/$run.vect" --steps 150 --tries 3 --seed 7 --no-kkt --device reference \
    >"$work/$run.out" 2>"$work/$run.err" || fail "tighten ($run): $(cat "$work/$run.err")"
done
# the written curve is the shortest road, and its comment says which
grep -c '^tightrope tighten: road [0-9] of 3: ropelength' "$work/a.err" | grep -qx 3 || fail "not 3 roads: $(cat "$work/a.err")"
best=$(awk '/road [0-9] of 3: ropelength/ { if (m == "" || $NF < m) m = $NF } END { print m }' "$work/a.err")
got=$("$tr" measure "$work/a.vect" | awk '$1 == "curve" { print $7 }')
awk -v b="$best" -v g="$got" 'BEGIN { d = b - g; if (d < 0) d = -d; exit !(d < 1e-8 * b) }' ||
  fail "wrote $got, the shortest road was $best"
grep -Eq '^# tries 3, seed 7: the shortest was road [1-3]$' "$work/a.vect" || fail "no tries comment"
# the same seed, the same roads
cmp -s <(grep -v '^#' "$work/a.vect") <(grep -v '^#' "$work/b.vect") || fail "seed 7 twice gave two curves"
# with levels (--refine-to) the roads are scouts: after the first they start again from the
# start, at other coarse counts, the second inflated; each stops at its coarse level, and the
# shortest scout alone is refined to --refine-to and written
"$tr" tighten "$work/s.vect" -o "$work/l.vect" --n 80 --refine-to 160 --steps 400 --tries 3 --no-kkt --device reference \
  >"$work/l.out" 2>"$work/l.err" || fail "tighten with levels: $(cat "$work/l.err")"
grep -q '^tightrope tighten: road 2 of 3: the start again, inflated 1.5 times, from another coarse count$' "$work/l.err" ||
  fail "road 2 is not the inflated start: $(cat "$work/l.err")"
grep -q '^tightrope tighten: road 3 of 3: the start again, from another coarse count$' "$work/l.err" ||
  fail "road 3 is not the start: $(cat "$work/l.err")"
best=$(awk '/road [0-9] of 3: ropelength/ { if (m == "" || $NF < m) { m = $NF; k = $4 } } END { print k }' "$work/l.err")
grep -Eq "^tightrope tighten: the shortest scout \(road $best, N [0-9]+\) refined to 160 vertices$" "$work/l.err" ||
  fail "the shortest scout was road $best, not what was refined: $(cat "$work/l.err")"
refined=$(awk '/^tightrope tighten: refined: N 160, ropelength/ { print $NF }' "$work/l.err")
[ -n "$refined" ] || fail "no refinement to 160: $(cat "$work/l.err")"
got=$("$tr" measure "$work/l.vect" | awk '$1 == "curve" { print $2, $7 }')
[ "${got%% *}" = 160 ] || fail "levels: wrote ${got%% *} vertices, not 160"
awk -v b="$refined" -v g="${got#* }" 'BEGIN { d = b - g; if (d < 0) d = -d; exit !(d < 1e-8 * b) }' ||
  fail "levels: wrote ${got#* }, the refined scout was $refined"
# a scout the engine took past N (a short knot at small N: the inflated road adds vertices)
# is resampled to N and written at N, not refused
"$tr" make torus 2 3 --n 64 -o "$work/s64.vect" >/dev/null || fail "make 64"
"$tr" tighten "$work/s64.vect" -o "$work/p.vect" --refine-to 80 --steps 600 --tries 2 --seed 5 --no-kkt \
  --device reference >"$work/p.out" 2>"$work/p.err" || fail "past N: $(cat "$work/p.err")"
grep -q 'shortest scout (road 2, N 96) resampled to 80 vertices' "$work/p.err" ||
  fail "past N: the inflated scout was not past N or not resampled: $(cat "$work/p.err")"
got=$("$tr" measure "$work/p.vect" | awk '$1 == "curve" { print $2 }')
[ "$got" = 80 ] || fail "past N: wrote $got vertices, not 80: $(cat "$work/p.err")"
# --shuffles S: the last S roads start from the start shuffled (tighten/shuffle.h), the same
# with the same seed
for run in s1 s2; do
  "$tr" tighten "$work/s.vect" -o "$work/$run.vect" --n 80 --refine-to 160 --steps 300 --tries 2 --shuffles 1 --seed 5 \
    --no-kkt --device reference >"$work/$run.out" 2>"$work/$run.err" || fail "--shuffles ($run): $(cat "$work/$run.err")"
done
grep -q '^tightrope tighten: road 2 of 2: the start shuffled' "$work/s1.err" || fail "road 2 not shuffled: $(cat "$work/s1.err")"
grep -q '^tightrope tighten: road 2 of 2: ropelength' "$work/s1.err" || fail "the shuffled road did not end: $(cat "$work/s1.err")"
cmp -s <(grep -v '^#' "$work/s1.vect") <(grep -v '^#' "$work/s2.vect") || fail "--shuffles, seed 5 twice gave two curves"
for bad in "--tries 2 --shuffles 2" "--shuffles 1" "--tries 3 --shuffles -1"; do
  # shellcheck disable=SC2086
  "$tr" tighten "$work/s.vect" -o "$work/x.vect" $bad 2>"$work/bad.err" && fail "$bad accepted"
  grep -q -- "--shuffles" "$work/bad.err" || fail "$bad: $(cat "$work/bad.err")"
done
# bad values and a resumed run are refused
for bad in 0 1001 x; do
  "$tr" tighten "$work/s.vect" -o "$work/x.vect" --tries $bad 2>"$work/bad.err" && fail "--tries $bad accepted"
  grep -q "bad --tries" "$work/bad.err" || fail "--tries $bad: $(cat "$work/bad.err")"
done
# --checkpoint: the roads share the path and the last road's end wrote it; the checkpoint left
# is the kept road's, so --resume goes on from the written curve (it once went on from road 3's
# state, 33.04 where the run wrote road 1's 32.86: the trefoil of 120 vertices, 100 steps a road,
# road 1 the shortest)
"$tr" make torus 2 3 --n 120 -o "$work/c.vect" >/dev/null || fail "make 120"
"$tr" tighten "$work/c.vect" -o "$work/c.out.vect" --tries 3 --steps 100 --checkpoint "$work/c.ckpt" --no-polish \
  --no-kkt --device reference >/dev/null 2>"$work/c.err" || fail "tighten --checkpoint: $(cat "$work/c.err")"
grep -q '^# tries 3, seed 1: the shortest was road 1$' "$work/c.out.vect" || fail "road 1 is not the kept one here: nothing tested"
"$tr" tighten --resume "$work/c.ckpt" -o "$work/c.res.vect" --no-kkt --device reference >/dev/null 2>&1 ||
  fail "--resume of the roads' checkpoint"
w=$("$tr" measure "$work/c.out.vect" | awk '$1 == "curve" { print $7 }')
r=$("$tr" measure "$work/c.res.vect" | awk '$1 == "curve" { print $7 }')
awk -v r="$r" -v w="$w" 'BEGIN { exit !(r <= w * (1 + 1e-12)) }' ||
  fail "resumed to $r from the checkpoint, the run wrote $w: the checkpoint is not the kept road's"
"$tr" tighten --resume "$work/none.ckpt" -o "$work/x.vect" --tries 2 2>"$work/res.err" && fail "--resume --tries accepted"
grep -q -- "--tries starts several" "$work/res.err" || fail "--resume --tries: $(cat "$work/res.err")"
exit 0
