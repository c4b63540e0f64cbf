#!/usr/bin/env bash
# A checkpoint that cannot be written is a warning, not the loss of the run
# (issue 26): the checkpoint's folder is removed while tighten runs; the run
# goes on, writes its output, exits 0 and says how many checkpoints failed.
# Usage: checkpoint_cli.sh TIGHTROPE WORK_DIR. Exit 0 pass, 1 fail.
set -u
tr=$1 work=$2
rm -rf "$work" && mkdir -p "$work/ck"
fail() { echo "FAIL: $*"; exit 1; }
"$tr" make torus 2 3 --n 200 -o "$work/s.vect" >/dev/null || fail "make"
# --n 200: at its own N (a loose start's route would make N 200 a goal
# that 3 s under load or the sanitizers may not reach: exit 1)
"$tr" tighten "$work/s.vect" -o "$work/t.vect" --n 200 --checkpoint "$work/ck/c.ckpt" --checkpoint-every 0.2 \
  --time-limit 3 --no-polish --no-kkt --quiet --device reference 2>"$work/err" &
pid=$!
sleep 1
[ -s "$work/ck/c.ckpt" ] || fail "no checkpoint after 1 s"
# moved away in one step: an rm -rf raced the writer (a checkpoint written
# into the folder while rm emptied it left it "not empty", and the run saw
# no failure); after the rename every write into ck/ fails
mv "$work/ck" "$work/ck.gone" || fail "could not move the checkpoint folder"
wait $pid
rc=$?
cat "$work/err"
[ "$rc" = 0 ] || fail "exit $rc"
[ -s "$work/t.vect" ] || fail "no output"
grep -Eq 'warning: [0-9]+ checkpoints? could not be written \(the run went on\)' "$work/err" || fail "no warning"
"$tr" measure "$work/t.vect" >/dev/null || fail "the output does not measure"
exit 0
