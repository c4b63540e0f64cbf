#!/usr/bin/env bash
# A tighten whose solve is stopped and resumed takes the unbroken run's
# Newton steps (issue 48 item 5; host/engine/solver_state.c): the tight
# N = 2400 trefoil resampled to 3600 goes to the second-order solver at once
# (some 190 Newton steps). With --checkpoint the solve's state goes to
# CKPT.newton every second; the run is stopped by SIGINT once one is there,
# and --resume goes on with the solve where it stopped. The resumed solve
# must take the steps the stopped one had left: stopped + resumed = the
# unbroken run's count, and the written curve is the unbroken run's (same
# ropelength to 1e-9 relative). A resume that ignored the state would
# start the solve again from the checkpoint's curve (mu back at mu0) and
# take well over the steps left. Also: a CKPT.newton that is not the one
# its checkpoint names is ignored with a note, and a file there that is no
# solver state is never written over.
# Usage: solver_state_resume.sh TIGHTROPE START WORK_DIR. Exit 0 pass, 1 fail.
set -u
tr=$1 start=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
common=(--device reference --no-kkt)
# "newton accepted: ropelength A -> B in T s, K steps": B and K
solved() { sed -n 's/.*newton accepted: ropelength [0-9.]* -> \([0-9.]*\) in [0-9.]* s, \([0-9]*\) steps.*/\1 \2/p' "$1"; }

# the unbroken run
"$tr" tighten "$start" --n 3600 -o "$work/u.vect" "${common[@]}" >"$work/u.err" 2>&1 || { cat "$work/u.err"; fail "unbroken run"; }
read -r rl_u k_u <<<"$(solved "$work/u.err")"
[ -n "${k_u:-}" ] || { cat "$work/u.err"; fail "the unbroken run did not report an accepted solve"; }

# the stopped run: SIGINT once the solve has written a state and a
# checkpoint that names it (the solver's first checkpoint, a rope with equal
# edges: a signal in the solve's first steps stops it with a result whose
# edges are not yet equal to the 1e-6 a resume asks of a checkpoint)
"$tr" tighten "$start" --n 3600 -o "$work/s.vect" "${common[@]}" --checkpoint "$work/c.ckpt" \
  --checkpoint-every 1 >"$work/s.err" 2>&1 &
pid=$!
for _ in $(seq 600); do
  grep -qs "^newton_state" "$work/c.ckpt" && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.1
done
kill -INT $pid 2>/dev/null
wait $pid
cat "$work/s.err"
[ -s "$work/c.ckpt.newton" ] || fail "no solver state beside the checkpoint"
grep -q "interrupted" "$work/s.err" || fail "the run was not stopped mid-solve"
grep -q "^newton_state [0-9a-f]\{16\}$" "$work/c.ckpt" || fail "the checkpoint names no solver state"
read -r rl_s k_s <<<"$(solved "$work/s.err")"
[ -n "${k_s:-}" ] || fail "the stopped run reported no solve"
cp "$work/c.ckpt" "$work/d.ckpt"

# resumed: the steps left, the same curve, the state removed once solved
"$tr" tighten --resume "$work/c.ckpt" -o "$work/r.vect" "${common[@]}" --checkpoint "$work/c.ckpt" \
  >"$work/r.err" 2>&1 || { cat "$work/r.err"; fail "resume exit $?"; }
cat "$work/r.err"
grep -q "the solve goes on from its state" "$work/r.err" || fail "the state was not taken"
read -r rl_r k_r <<<"$(solved "$work/r.err")"
echo "unbroken: $k_u steps, ropelength $rl_u; stopped after $k_s, resumed $k_r more, ropelength $rl_r"
[ "$((k_s + k_r))" -eq "$k_u" ] || fail "stopped $k_s + resumed $k_r steps, the unbroken run took $k_u"
[ -e "$work/c.ckpt.newton" ] && fail "the state of a converged solve was left behind"
grep -q "^newton_state" "$work/c.ckpt" && fail "the last checkpoint names the state of a converged solve"
got_u=$("$tr" measure "$work/u.vect" | awk '$1 == "curve" {print $3}')
got_r=$("$tr" measure "$work/r.vect" | awk '$1 == "curve" {print $3}')
awk -v u="$got_u" -v r="$got_r" 'BEGIN { d = u - r; if (d < 0) d = -d; exit !(u > 0 && d <= 1e-9 * u) }' ||
  fail "written ropelength: unbroken $got_u, stopped and resumed $got_r"

# a state that is not the one named (a copy from elsewhere, one byte off) is
# ignored with a note; a file that is no state is never written over
# (the run then solves from the checkpoint's curve: 3 s of it are enough,
# the limit counting the stopped run's seconds and the command's reading of
# the checkpoint; under a sanitizer 3 s ended before the solve's first
# checkpoint, which is what says the file was left alone: 30 s there)
cp "$work/d.ckpt" "$work/e.ckpt"
printf 'not a solver state\n' >"$work/e.ckpt.newton"
before=$(awk '$1 == "state" {print $6}' "$work/e.ckpt")
more=3
[ -n "${ASAN_OPTIONS:-}" ] && more=30
limit=$(awk -v b="$(printf '%.3f' "$before")" -v m=$more 'BEGIN { printf "%.1f", b + m }')
"$tr" tighten --resume "$work/e.ckpt" -o "$work/e.vect" "${common[@]}" --checkpoint "$work/e.ckpt" \
  --checkpoint-every 1 --time-limit "$limit" >"$work/e.err" 2>&1
cat "$work/e.err"
grep -q "e.ckpt.newton ignored: it is not the solver state the checkpoint" "$work/e.err" ||
  fail "a state that is not the named one was not noted as ignored"
grep -q "the solve goes on from its state" "$work/e.err" && fail "a state that is not the named one was taken"
grep -q "e.ckpt.newton is not a solver state: left alone" "$work/e.err" ||
  fail "the solve's state was not noted as not kept"
[ "$(cat "$work/e.ckpt.newton")" = "not a solver state" ] || fail "a file that is no solver state was written over"
exit 0
