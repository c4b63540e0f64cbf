#!/usr/bin/env bash
# Hostile-user checks of 'tightrope batch' (issue 45): a batch that writes over
# another knot's start, a record or checkpoint of another start taken for the
# knot's, --merge taking another knot under the same name, and a bad option
# found only when its knot comes. Usage: hostile_batch.sh CASE TIGHTROPE WORK_DIR.
# Exit 0 pass, 1 fail, 77 skipped. Every knot is a small circle or trefoil on
# the serial reference (a second or less). What is checked are facts: exit
# status, one line on stderr naming FILE:LINE, files byte for byte and by inode,
# which start a table row came from (its N: every component of a start of n
# vertices stays at n here), and a regular n-gon's closed-form ropelength
# 2n tan(pi/n) (a circle's tight shape), never numbers of our own earlier runs.
set -u
. "$(cd "$(dirname "$0")" && pwd)/cli_testlib.sh"
case_=$1 tr=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
export TIGHTROPE_DEVICE=reference
tab=$'\t'
# col TABLE KNOT COLUMN: the knot's value under the column's header
col() {
  awk -F'\t' -v k="$2" -v c="$3" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) n = i; next } $1 == k { print $n }' "$1"
}
# ngon TABLE KNOT N: the knot's row is a regular N-gon's, N vertices, ropelength 2N tan(pi/N)
ngon() {
  [ "$(col "$1" "$2" N)" = "$3" ] || fail "$1: $2 has N '$(col "$1" "$2" N)', its start has $3: $(cat "$1")"
  awk -v r="$(col "$1" "$2" ropelength)" -v n="$3" 'BEGIN { pi = atan2(0, -1); w = 2 * n * sin(pi / n) / cos(pi / n)
      d = (r - w) / w; exit !(d < 1e-8 && -d < 1e-8) }' || fail "$1: $2's ropelength $(col "$1" "$2" ropelength) is no $3-gon's"
}
# sums FILES...: their bytes and inodes, to compare before and after
sums() { for f in "$@"; do printf '%s %s\n' "$(stat -c %i "$f")" "$(md5sum <"$f")"; done; }
circle() { "$tr" make circle --n "$1" -o "$2" >/dev/null || fail "make circle $1"; }
trefoil() { "$tr" make torus 2 3 --n "$1" -o "$2" >/dev/null || fail "make trefoil $1"; }

case $case_ in
cross)
  # Issue 45, serious 3: y's curve goes to xo/y.vect, which is x's start. Before,
  # y's circle was written over the trefoil there and x tabulated as a circle,
  # exit 0. Now refused before anything runs, whatever spells the collision.
  circle 40 c.vect
  trefoil 64 t.vect
  mkdir xo && cp t.vect xo/y.vect
  printf 'y\tc.vect\nx\txo/y.vect\n' >cross.tsv
  before=$(sums xo/y.vect)
  refused 2 '^tightrope batch: cross.tsv:2: .*xo/y.vect.* y' "$tr" batch cross.tsv -o xo -- --steps 3
  [ "$(sums xo/y.vect)" = "$before" ] || fail "x's start xo/y.vect changed"
  [ "$(ls -A xo)" = y.vect ] || fail "written into xo: $(ls -A xo)"
  # ... by a symbolic link in OUT to the start (the writer replaces a link's target)
  mkdir lo && ln -s ../t.vect lo/y.vect
  printf 'y\tc.vect\nx\tt.vect\n' >link.tsv
  before=$(sums t.vect)
  refused 2 '^tightrope batch: link.tsv:2: .*t.vect' "$tr" batch link.tsv -o lo -- --steps 3
  [ "$(sums t.vect)" = "$before" ] && [ -L lo/y.vect ] || fail "t.vect or the link changed"
  # ... by ../ and a hard link
  mkdir ho && ln t.vect ho/y.vect
  refused 2 '^tightrope batch: link.tsv:2: ' "$tr" batch link.tsv -o ho/../ho -- --steps 3
  [ "$(sums t.vect)" = "$before" ] || fail "t.vect changed through a hard link"
  # ... a knot's retry round's curve (OUT/retry-1/NAME.vect)
  mkdir -p ro/retry-1 && cp t.vect ro/retry-1/y.vect
  printf 'y\tc.vect\nx\tro/retry-1/y.vect\n' >retry.tsv
  printf 'knot\tropelength\ny\t1\n' >ref.tsv
  refused 2 '^tightrope batch: retry.tsv:2: .*retry 1 curve' "$tr" batch retry.tsv -o ro --compare ref.tsv --retry 1
  cmp -s t.vect ro/retry-1/y.vect || fail "ro/retry-1/y.vect changed"
  # ... the manifest itself as the table, and a folder of starts as its own OUT
  mkdir mo && printf 'y\t../c.vect\n' >mo/table.tsv && cp mo/table.tsv m.copy
  refused 2 '^tightrope batch: the manifest mo/table.tsv .*table' "$tr" batch mo/table.tsv -o mo --table-only
  cmp -s m.copy mo/table.tsv || fail "the manifest was written over"
  mkdir so && cp c.vect so/a.vect
  refused 2 'the start so/a.vect of a ' "$tr" batch so -o so
  cmp -s c.vect so/a.vect && [ "$(ls -A so)" = a.vect ] || fail "so changed: $(ls -A so)"
  # the same manifest into a folder of its own: each knot is what its start is
  run "$tr" batch cross.tsv -o fresh -- --steps 3
  [ "$rc" = 0 ] || fail "into a fresh folder: exit $rc: $(cat err)"
  ngon fresh/table.tsv y 40
  [ "$(col fresh/table.tsv x N)" = 64 ] || fail "x is not the trefoil of 64 vertices: $(cat fresh/table.tsv)"
  ;;
stale_row)
  # Issue 45, milder 7: a record stays after the manifest points its knot at
  # another file, or the file is edited; the table showed the old result. Now
  # the record names its start (a hash of its bytes) and is redone.
  circle 40 c40.vect
  circle 50 c50.vect
  circle 60 c60.vect
  printf 'k\tc40.vect\nj\tc50.vect\n' >m.tsv
  run "$tr" batch m.tsv -o o
  [ "$rc" = 0 ] || fail "first batch: exit $rc: $(cat err)"
  ngon o/table.tsv k 40
  printf 'k\tc60.vect\nj\tc50.vect\n' >m.tsv
  # another job's table (--only j) leaves k's record of another start out
  run "$tr" batch m.tsv -o o --only j
  [ "$rc" = 0 ] || fail "--only j: exit $rc: $(cat err)"
  [ -z "$(col o/table.tsv k N)" ] || fail "k's record of another start tabulated: $(cat o/table.tsv)"
  grep -q 'k: .*another start' err || fail "not said: $(cat err)"
  run "$tr" batch m.tsv -o o --table-only
  [ -z "$(col o/table.tsv k N)" ] || fail "--table-only tabulated k's record of another start"
  run "$tr" batch m.tsv -o o
  [ "$rc" = 0 ] || fail "k pointed at c60.vect: exit $rc: $(cat err)"
  ngon o/table.tsv k 60
  ngon o/table.tsv j 50
  # the start edited in place: same name, other bytes
  cp c40.vect c60.vect
  run "$tr" batch m.tsv -o o
  [ "$rc" = 0 ] || fail "c60.vect edited: exit $rc: $(cat err)"
  ngon o/table.tsv k 40
  # nothing changed: nothing runs again
  cp o/k.row.tsv row.before
  run "$tr" batch m.tsv -o o
  grep -q tightening err && fail "a knot with its record ran again: $(cat err)"
  cmp -s row.before o/k.row.tsv || fail "k's record changed"
  # a record of before the start column is kept, said, and tabulated
  cut -f1-14 o/k.row.tsv >old && mv old o/k.row.tsv
  run "$tr" batch m.tsv -o o
  [ "$rc" = 0 ] && grep -q 'k: done before, skipped (its record names no start' err || fail "old record: exit $rc: $(cat err)"
  ngon o/table.tsv k 40
  [ "$(col o/table.tsv k start)" = - ] || fail "an old record's start: $(col o/table.tsv k start)"
  ;;
stale_checkpoint)
  # A checkpoint left by SIGTERM, then the manifest points the knot at
  # another start: resumed, the other curve was tabulated under the name.
  # Now the checkpoint is of the start it names beside it, and the knot
  # starts afresh.
  trefoil 128 t.vect
  circle 60 c60.vect
  printf 'k\tt.vect\t-\t--time-limit 8\n' >m.tsv
  "$tr" batch m.tsv -o o --checkpoint-every 0.2 2>err.log &
  pid=$!
  for _ in $(seq 100); do [ -f o/k.ckpt ] && break; sleep 0.1; done
  kill -TERM $pid
  wait $pid
  [ -f o/k.ckpt ] || fail "no checkpoint to test with: $(cat err.log)"
  printf 'k\tc60.vect\t-\t--time-limit 8\n' >m.tsv
  run "$tr" batch m.tsv -o o
  [ "$rc" = 0 ] || fail "exit $rc: $(cat err)"
  ngon o/table.tsv k 60
  [ "$(col o/table.tsv k resumed)" = 0 ] || fail "k resumed another start's checkpoint"
  ls o | grep -Eq '\.(ckpt|start)$' && fail "checkpoint files left: $(ls o)"
  true
  ;;
resume_shuffles)
  # A knot with --tries and --shuffles, stopped by SIGTERM, resumes: the
  # resumed run leaves out --shuffles with --tries (tighten refuses
  # --shuffles without --tries above it); it failed before.
  trefoil 128 t.vect
  printf 'k\tt.vect\t-\t--tries 2 --shuffles 1 --time-limit 8\n' >m.tsv
  "$tr" batch m.tsv -o o --checkpoint-every 0.2 2>err.log &
  pid=$!
  for _ in $(seq 100); do [ -f o/k.ckpt ] && break; sleep 0.1; done
  kill -TERM $pid
  wait $pid
  [ -f o/k.ckpt ] || fail "no checkpoint to test with: $(cat err.log)"
  run "$tr" batch m.tsv -o o
  [ "$rc" = 0 ] || fail "resume: exit $rc: $(cat err)"
  [ "$(col o/table.tsv k resumed)" = 1 ] || fail "k did not resume: $(cat o/table.tsv)"
  ;;
merge_other_start)
  # Issue 45, milder 7: --merge took a different knot under the same name (a
  # trefoil replaced by an unknot, 32.84 -> 6.29). Now refused, nothing
  # merged, when the records come from other starts.
  trefoil 64 t.vect
  circle 64 c.vect
  printf 'tref\tt.vect\t-\t--steps 20\n' >ma.tsv
  printf 'tref\tc.vect\n' >mb.tsv
  "$tr" batch ma.tsv -o a --quiet 2>err && "$tr" batch mb.tsv -o b --quiet 2>err || fail "batches: $(cat err)"
  before=$(sums a/tref.vect a/tref.row.tsv a/table.tsv)
  refused 2 '^tightrope batch: --merge: b/tref.row.tsv is of another start than ma.tsv:1' "$tr" batch ma.tsv -o a --merge b
  [ "$(sums a/tref.vect a/tref.row.tsv a/table.tsv)" = "$before" ] || fail "a changed"
  refused 2 'another start' "$tr" batch ma.tsv -o d --merge b
  [ -e d ] && fail "a refused merge made its folder"
  # the same start from another run (more steps: shorter) is merged
  printf 'tref\tt.vect\t-\t--steps 60\n' >mc.tsv
  "$tr" batch mc.tsv -o c --quiet 2>err || fail "batch c: $(cat err)"
  run "$tr" batch ma.tsv -o a --merge c
  [ "$rc" = 0 ] || fail "merge c: exit $rc: $(cat err)"
  cmp -s a/tref.vect c/tref.vect || awk -v a="$(col a/table.tsv tref ropelength)" -v c="$(col c/table.tsv tref ropelength)" \
    'BEGIN { exit !(a <= c) }' || fail "c's shorter trefoil not merged"
  # a record of before the start column: merged on its name, and said so
  cut -f1-14 b/tref.row.tsv >old && mv old b/tref.row.tsv
  run "$tr" batch mb.tsv -o e --merge b
  [ "$rc" = 0 ] || fail "old record: exit $rc: $(cat err)"
  grep -q 'names no start' err || fail "not said: $(cat err)"
  ;;
options_early)
  # Issue 45, rough edge: a bad option in a manifest row or --retry-options
  # failed only when its knot ran. Now every row's and every recipe's options
  # are checked before anything runs: one line, exit 2, no output folder.
  circle 40 c.vect
  trefoil 64 t.vect
  printf 'a\tt.vect\t-\t--steps 5\nb\tc.vect\t-\t--tries x\n' >m.tsv
  refused 2 "^tightrope batch: m.tsv:2: bad --tries 'x'" "$tr" batch m.tsv -o o
  printf 'a\tt.vect\t-\t--steps 5\n# comment\nb\tc.vect\t-\t--bogus\n' >m.tsv
  refused 2 "^tightrope batch: m.tsv:3: unknown option '--bogus'" "$tr" batch m.tsv -o o
  refused 2 "^tightrope batch: m.tsv:3: unknown option '--bogus'" "$tr" batch m.tsv --list
  printf 'a\tt.vect\t-\t--tries 3 --shuffles 2\nb\tc.vect\t-\t--steps 5\n' >m.tsv
  printf 'knot\tropelength\na\t1\nb\t1\n' >ref.tsv
  refused 2 "^tightrope batch: --retry-options '--tries 0': bad --tries '0'" \
    "$tr" batch m.tsv -o o --compare ref.tsv --retry 2 --retry-options "--tries 4" --retry-options "--tries 0"
  # a recipe that fails only with a line's options names the line
  refused 2 "^tightrope batch: --retry-options '--tries 2' with m.tsv:1: .*--shuffles" \
    "$tr" batch m.tsv -o o --compare ref.tsv --retry 1 --retry-options "--tries 2"
  refused 2 "^tightrope batch: the tighten options after --: bad --steps '0'" "$tr" batch m.tsv -o o -- --steps 0
  [ -e o ] && fail "a refused batch made its output folder: $(ls -A o)"
  true
  ;;
*) fail "unknown case $case_" ;;
esac
echo ok
exit 0
