#!/usr/bin/env bash
# The second-order solver writes checkpoints (issue 26: checkpoints in every
# stage): the tight N = 2400 trefoil resampled to 2600 goes to the solver
# before the engine's first step, so a checkpoint that appears while the
# solver has not reported is the solver's. The run is killed (SIGKILL) as
# soon as one appears; --resume goes on from it and ends no longer than it.
# Usage: solver_checkpoint.sh TIGHTROPE START WORK_DIR. Exit 0 pass, 1 fail.
set -u
tr=$1 start=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
"$tr" tighten "$start" --n 2600 -o "$work/t.vect" --checkpoint "$work/c.ckpt" --checkpoint-every 0.2 \
  --device reference --no-kkt >"$work/err" 2>&1 &
pid=$!
for _ in $(seq 600); do
  [ -s "$work/c.ckpt" ] && break
  sleep 0.1
done
kill -9 $pid 2>/dev/null
wait $pid 2>/dev/null
[ -s "$work/c.ckpt" ] || fail "no checkpoint within 60 s"
cat "$work/err"
grep -q "newton" "$work/err" && fail "the solver had finished: the checkpoint is not the solver's"
[ -e "$work/t.vect" ] && fail "an output was written before the kill"
grep -q "^comp 2600 1 " "$work/c.ckpt" || fail "the checkpoint is not the 2600-vertex curve"
"$tr" tighten --resume "$work/c.ckpt" -o "$work/t.vect" --device reference --no-kkt --time-limit 60 \
  >"$work/err2" 2>&1 || { cat "$work/err2"; fail "resume exit $?"; }
cat "$work/err2"
# the resumed solve starts from the checkpoint: "ropelength A -> B", A the
# checkpoint's (the spline start is 35.1 at MinRad 1; tight means < 32.7432).
# Accepted or rejected: where the checkpoint is the solve's last stretch (a
# slow build, ASan: the first iterate at violation 1e-7 comes late) the
# solver finds nothing shorter, B = A, and the run writes the checkpoint's
# curve; what is asserted is that it went to the solver and ended no longer
ab=$(sed -n 's/.*newton \(accepted\|rejected\): ropelength \([0-9.]*\) -> \([0-9.]*\).*/\2 \3/p' "$work/err2")
[ -n "$ab" ] || fail "the resumed run did not go to the solver"
got=$("$tr" measure "$work/t.vect" | awk '$1 == "curve" {print $7}')
echo "checkpoint and resumed solve: $ab; written $got"
awk -v ab="$ab" -v g="$got" 'BEGIN { split(ab, v, " "); exit !(v[1] < 32.7432 && v[2] <= v[1] && g <= v[1] + 1e-9) }' ||
  fail "checkpoint and resumed: $ab, written $got"
exit 0
