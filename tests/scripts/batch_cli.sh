#!/usr/bin/env bash
# CLI checks of 'tightrope batch'. Usage: batch_cli.sh CASE TIGHTROPE SOURCE_DIR WORK_DIR
# Exit 0 pass, 1 fail, 77 skipped. Every case tightens two or three small knots on the
# serial reference (seconds each); the numbers checked are published bounds or what
# tightrope measure says of the written curves, never figures taken from our own runs.
set -u
case_=$1 tr=$2 src=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
export TIGHTROPE_DEVICE=reference

# Three small starts and a manifest of them (N per component, a time limit each).
make_knots() {
  "$tr" make torus 2 3 --n 64 -o t23.vect >/dev/null || fail "make trefoil"
  "$tr" make hopf --n 40 -o hopf.vect >/dev/null || fail "make hopf"
  "$tr" make torus 2 5 --n 100 -o t25.vect >/dev/null || fail "make T(2,5)"
  printf 'name\tfile\tN\toptions\n# a comment\ntrefoil\tt23.vect\t%s\t--time-limit 3\nhopf\thopf.vect\t%s\t--time-limit 3\n' \
    "$1" "$2" >m.tsv
  printf 't25\tt25.vect\t%s\t--time-limit 3\n' "$3" >>m.tsv
}
names() { awk -F'\t' 'NR > 1 { print $1 }' "$1"; }
col() { # col TABLE KNOT COLUMN: the value in the knot's row under the column's header
  awk -F'\t' -v k="$2" -v c="$3" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) n = i; next } $1 == k { print $n }' "$1"
}

# The finished table: one row per knot of the manifest, in its order; every row's numbers are
# those of its written curve as measure reads it, at thickness 1, above the published lower
# bounds (any nontrivial knot >= 31.32, Denne, Diao and Sullivan 2006; the Hopf link >= 8 pi,
# Cantarella, Kusner and Sullivan 2002); no checkpoint or temporary file is left (check_table
# OUT killed: temporaries allowed).
check_table() {
  local out=$1
  [ "$(names "$out/table.tsv" | tr '\n' ' ')" = "trefoil hopf t25 " ] || fail "table rows: $(names "$out/table.tsv" | tr '\n' ' ')"
  for k in trefoil hopf t25; do
    local rl th
    rl=$(col "$out/table.tsv" $k ropelength) th=$(col "$out/table.tsv" $k thickness)
    local m
    m=$("$tr" measure "$out/$k.vect" --json) || fail "measure $k"
    local mrl
    mrl=$(echo "$m" | grep -o '"ropelength": [^,]*' | head -1 | cut -d' ' -f2) # the whole curve's, before per_component
    awk -v a="$rl" -v b="$mrl" 'BEGIN { exit !(a - b < 1e-8 * b && b - a < 1e-8 * b) }' || fail "$k: table $rl, measure $mrl"
    awk -v t="$th" 'BEGIN { exit !(t > 1 - 1e-9 && t < 1 + 1e-9) }' || fail "$k: thickness $th"
    local lo=31.32
    [ $k = hopf ] && lo=25.1327412
    awk -v a="$rl" -v lo=$lo 'BEGIN { exit !(a >= lo) }' || fail "$k: ropelength $rl below $lo"
  done
  ls "$out"/*.ckpt >/dev/null 2>&1 && fail "checkpoints left: $(ls "$out")"
  # SIGKILL during an atomic write leaves its hidden temporary (text_file.h), nothing else does
  [ "${2:-}" = killed ] || ! ls -a "$out" | grep -q '^\.tr\.' || fail "temporary files left: $(ls -a "$out")"
  [ "$(wc -l <"$out/table.tsv")" = 4 ] || fail "table lines"
  cmake -DCMD="cat;$out/table.json" -DMEMBER="knots;2;ropelength" -DTYPE=NUMBER -P "$src/tests/scripts/json_valid.cmake" \
    >/dev/null || fail "table.json"
  # the table is what the records say: rebuilding it changes nothing
  cp "$out/table.tsv" table.before
  "$tr" batch m.tsv -o "$out" --table-only 2>/dev/null || fail "--table-only"
  cmp -s table.before "$out/table.tsv" || fail "--table-only rebuilds another table"
}

case $case_ in
kill_resume)
  # The batch killed (SIGKILL) at random moments and started again: it finishes with every
  # knot once. A knot done before a kill is not done again (its record and curve stay as they
  # were); one that had a checkpoint at a kill resumes from it.
  make_knots 128 80 200
  seed=${TR_BATCH_SEED:-$RANDOM}
  echo "seed $seed (TR_BATCH_SEED reruns it)"
  RANDOM=$seed
  declare -A had_ckpt done_sum
  for round in 1 2 3; do
    "$tr" batch m.tsv -o out --checkpoint-every 0.3 2>>err.log &
    pid=$!
    t=$(awk -v r=$RANDOM 'BEGIN { printf "%.2f", 0.2 + 4 * r / 32767 }')
    echo "round $round: kill after $t s"
    sleep "$t"
    kill -9 $pid 2>/dev/null
    wait $pid
    st=$?
    [ $st = 0 ] && echo "round $round: the batch ended before the kill"
    [ $st = 0 ] || [ $st = 137 ] || fail "round $round: exit $st: $(tail -3 err.log)"
    for k in trefoil hopf t25; do
      if [ -f out/$k.row.tsv ]; then
        [ -n "${done_sum[$k]:-}" ] || done_sum[$k]=$(cat out/$k.row.tsv out/$k.vect | md5sum)
      elif [ -f out/$k.ckpt ]; then
        had_ckpt[$k]=1
      fi
    done
  done
  "$tr" batch m.tsv -o out --checkpoint-every 0.3 2>>err.log || fail "final run: exit $?: $(tail -3 err.log)"
  for k in "${!done_sum[@]}"; do
    [ "$(cat out/$k.row.tsv out/$k.vect | md5sum)" = "${done_sum[$k]}" ] || fail "$k was done again after a kill"
  done
  for k in "${!had_ckpt[@]}"; do
    [ "$(col out/table.tsv $k resumed)" = 1 ] || fail "$k had a checkpoint and did not resume from it"
  done
  echo "done before a kill: ${!done_sum[*]}; resumed: ${!had_ckpt[*]}"
  check_table out killed
  ;;
sigterm)
  # SIGTERM stops the running knot at its next step: exit 1, its checkpoint kept, no record;
  # the next run resumes it.
  make_knots 128 80 200
  "$tr" batch m.tsv -o out --checkpoint-every 0.3 2>err.log &
  pid=$!
  for _ in $(seq 100); do [ -f out/hopf.ckpt ] || [ -f out/trefoil.ckpt ] && break; sleep 0.1; done
  kill -TERM $pid
  wait $pid
  st=$?
  [ $st = 1 ] || fail "exit $st after SIGTERM (want 1): $(cat err.log)"
  grep -q 'interrupted' err.log || fail "no message: $(cat err.log)"
  running=$(ls out/*.ckpt 2>/dev/null | head -1)
  [ -n "$running" ] || fail "no checkpoint after SIGTERM: $(ls out)"
  k=$(basename "$running" .ckpt)
  [ -f out/$k.row.tsv ] && fail "$k recorded as done"
  grep -q "^batch: interrupted; $k resumes from its checkpoint" err.log || fail "no resume said: $(cat err.log)"
  "$tr" batch m.tsv -o out 2>>err.log || fail "second run: exit $?"
  [ "$(col out/table.tsv $k resumed)" = 1 ] || fail "$k did not resume"
  check_table out
  # a knot whose roads are scouts (--tries on a route of levels) writes no checkpoint: it is
  # said to start again, not to resume
  printf 'name\tfile\tN\toptions\nscouted\tt25.vect\t400\t--scale --tries 4 --time-limit 60\n' >s.tsv
  "$tr" batch s.tsv -o sout 2>serr.log &
  pid=$!
  for _ in $(seq 100); do grep -q 'scouted: tightening' serr.log && break; sleep 0.1; done
  sleep 1
  kill -TERM $pid
  wait $pid
  [ -f sout/scouted.ckpt ] && fail "a scout wrote a checkpoint"
  grep -q "^batch: interrupted; scouted starts again (its run wrote no checkpoint)" serr.log ||
    fail "not said to start again: $(cat serr.log)"
  ;;
lock)
  # A second batch over the same folder leaves the knot the first is running alone.
  make_knots 128 80 200
  "$tr" batch m.tsv -o out --checkpoint-every 0.2 2>err.log &
  pid=$!
  for _ in $(seq 100); do [ -f out/trefoil.ckpt ] && break; sleep 0.05; done
  [ -f out/trefoil.ckpt ] || fail "the first batch never checkpointed the trefoil: $(cat err.log)"
  "$tr" batch m.tsv -o out --only trefoil 2>err2.log || fail "second batch: exit $?: $(cat err2.log)"
  wait $pid || fail "first batch: exit $?: $(cat err.log)"
  grep -q "trefoil: another batch process is running it" err2.log || fail "second batch: $(cat err2.log)"
  grep -q "trefoil: resuming" err.log err2.log && fail "the trefoil was taken over"
  check_table out
  ;;
manifest_errors)
  # A bad manifest line: one line naming FILE:LINE, exit 2, nothing tightened.
  make_knots - - -
  bad() { # bad WANT LINE...: a manifest of the lines must fail with WANT
    local want=$1
    shift
    printf '%s\n' "$@" >bad.tsv
    "$tr" batch bad.tsv -o badout >/dev/null 2>err
    local st=$?
    [ $st = 2 ] || fail "exit $st for: $*"
    [ "$(wc -l <err)" = 1 ] || fail "not one line: $(cat err)"
    grep -q "^tightrope batch: bad.tsv:$want" err || fail "want '$want', got: $(cat err)"
    [ -e badout ] && fail "output folder made for a bad manifest"
    return 0
  }
  tab=$'\t'
  bad "2: bad N 'x'" "a${tab}t23.vect" "b${tab}hopf.vect${tab}x"
  bad "3: bad N '3'" "# c" "a${tab}t23.vect" "b${tab}hopf.vect${tab}3"
  bad "3: name 'a' already given on line 1" "a${tab}t23.vect" "" "a${tab}hopf.vect"
  bad "1: bad name '../x'" "../x${tab}t23.vect"
  bad "1: start nothere.vect: No such file" "a${tab}nothere.vect"
  bad "2: option -o: batch sets it" "a${tab}t23.vect" "b${tab}hopf.vect${tab}-${tab}-o x.vect"
  bad "1: N is 100 and the options give --refine-to" "a${tab}t23.vect${tab}100${tab}--refine-to 200"
  bad "1: more than 4" "a${tab}t23.vect${tab}100${tab}--scale${tab}x"
  bad "1: expected name" "a"
  # starts by name (issue 47): an unknown name with the nearest, a missing one, the wrong kind
  bad "2: no knot named '4_99' in KnotInfo's table .*nearest: 4_1" "a${tab}knot 3_1" "b${tab}knot 4_99"
  bad "1: 'knot' names no knot" "a${tab}knot"
  bad "1: 'link' names no link" "a${tab}link:"
  bad "1: L2a1{0} is a link, not a knot" "a${tab}knot L2a1"
  bad "1: 3_1 is a knot, not a link" "a${tab}link 3_1"
  bad "1: no link named 'L12a1'" "a${tab}link L12a1"
  # a file whose name begins with the words: ./
  "$tr" make torus 2 3 --n 64 -o "knot 3_1.vect" >/dev/null || fail "make 'knot 3_1.vect'"
  printf 'a\t./knot 3_1.vect\n' >dot.tsv
  [ "$("$tr" batch dot.tsv --list 2>&1)" = a ] || fail "./knot 3_1.vect is not a file: $("$tr" batch dot.tsv --list 2>&1)"
  # a bad tighten option on any line is refused before any knot runs (issue 45)
  bad "2: unknown option '--bogus'" "b${tab}hopf.vect${tab}-${tab}--time-limit 1" "a${tab}t23.vect${tab}-${tab}--bogus"
  # usage errors
  "$tr" batch m.tsv -o o2 --job 2 --jobs 2 2>err && fail "--job 2 --jobs 2 accepted"
  "$tr" batch m.tsv -o o2 --only nosuch 2>err && fail "--only nosuch accepted"
  grep -q "no knot 'nosuch'" err || fail "--only message: $(cat err)"
  "$tr" batch m.tsv -o o2 -- --checkpoint x 2>err && fail "-- --checkpoint accepted"
  true
  ;;
folder_compare)
  # A folder of curves: knots named by file, in name order; --compare adds the reference's
  # values and ours - reference, matching 3.1 to 3_1 (the reference is made up here).
  make_knots - - -
  mkdir starts && cp t23.vect starts/3.1.vect && cp hopf.vect starts/hopf.vect && echo "not a curve" >starts/notes.md
  printf 'knot\tN\tropelength(L/tau)\n3_1\t400\t30.5\n5_2\t400\t49.5\n' >ref.tsv
  "$tr" batch starts -o out --compare ref.tsv -- --time-limit 2 2>err.log || fail "exit $?: $(cat err.log)"
  [ "$(names out/table.tsv | tr '\n' ' ')" = "3.1 hopf " ] || fail "rows: $(names out/table.tsv)"
  rl=$(col out/table.tsv 3.1 ropelength)
  [ "$(col out/table.tsv 3.1 ref_ropelength)" = 30.5000000000 ] || fail "ref: $(cat out/table.tsv)"
  [ "$(col out/table.tsv 3.1 ref_N)" = 400 ] || fail "ref_N"
  d=$(col out/table.tsv 3.1 diff) p=$(col out/table.tsv 3.1 diff_pct)
  awk -v r="$rl" -v d="$d" -v p="$p" 'BEGIN { e = r - 30.5; exit !(d - e < 1e-9 && e - d < 1e-9 && (p - 100 * e / 30.5)^2 < 1e-8) }' ||
    fail "diff $d, pct $p for ropelength $rl"
  [ "$(col out/table.tsv hopf ref_ropelength)" = - ] || fail "hopf has a reference"
  cmake -DCMD="cat;out/table.json" -DMEMBER="knots;1;ref_ropelength" -DTYPE=NULL -P "$src/tests/scripts/json_valid.cmake" \
    >/dev/null || fail "table.json: hopf's reference not null"
  cmake -DCMD="cat;out/table.json" -DMEMBER="knots;0;diff" -DTYPE=NUMBER -P "$src/tests/scripts/json_valid.cmake" \
    >/dev/null || fail "table.json: no diff"
  # a bad reference line names its FILE:LINE
  printf 'knot\tN\tropelength\n3_1\t400\tlong\n' >badref.tsv
  "$tr" batch starts -o out --compare badref.tsv 2>err && fail "a bad reference accepted"
  grep -q "badref.tsv:2:" err || fail "reference error: $(cat err)"
  ;;
jobs)
  # --job I --jobs J: disjoint parts that cover the batch; run one after the other into one
  # folder, they leave the whole table.
  make_knots 80 60 120
  a=$("$tr" batch m.tsv --list --job 0 --jobs 2) b=$("$tr" batch m.tsv --list --job 1 --jobs 2)
  [ "$(printf '%s\n%s\n' "$a" "$b" | sort | tr '\n' ' ')" = "hopf t25 trefoil " ] || fail "parts: [$a] [$b]"
  "$tr" batch m.tsv -o out --job 1 --jobs 2 2>err.log || fail "job 1: $(cat err.log)"
  [ "$(names out/table.tsv | tr '\n' ' ')" = "$(echo $b) " ] || fail "after job 1: $(names out/table.tsv)"
  "$tr" batch m.tsv -o out --job 0 --jobs 2 2>>err.log || fail "job 0: $(cat err.log)"
  check_table out
  ;;
merge)
  # --merge: the shorter of two batches' results per knot, curve and record together, at the
  # same N only; merging again changes nothing; each row names the seed and road it came from.
  make_knots - - -
  # a's knots stopped early, so b's trefoil is shorter (whichever is, the merge keeps it)
  "$tr" batch m.tsv -o a -- --steps 40 2>err.log || fail "batch a: $(cat err.log)"
  "$tr" batch m.tsv -o b --only trefoil -- --seed 5 2>err.log || fail "batch b: $(cat err.log)"
  [ "$(col a/table.tsv trefoil seed) $(col a/table.tsv trefoil road)" = "1 1" ] || fail "a's seed and road"
  [ "$(col b/table.tsv trefoil seed) $(col b/table.tsv trefoil road)" = "5 1" ] || fail "b's seed and road"
  cp -r a c
  "$tr" batch m.tsv -o c --merge b 2>err.log || fail "merge: $(cat err.log)"
  grep -q 'trefoil: .* -> .* from b' err.log || fail "b's shorter trefoil not taken: $(cat err.log)"
  ra=$(col a/table.tsv trefoil ropelength) rb=$(col b/table.tsv trefoil ropelength) rc=$(col c/table.tsv trefoil ropelength)
  best=$(awk -v a="$ra" -v b="$rb" 'BEGIN { print (b < a ? b : a) }')
  [ "$rc" = "$best" ] || fail "merged trefoil $rc, a $ra, b $rb"
  for k in hopf t25; do
    [ "$(col c/table.tsv $k ropelength)" = "$(col a/table.tsv $k ropelength)" ] || fail "merge changed $k"
  done
  check_table c
  cp c/table.tsv merged.before
  "$tr" batch m.tsv -o c --merge b 2>err.log || fail "merge again: $(cat err.log)"
  cmp -s merged.before c/table.tsv || fail "merging twice changed the table"
  # into a new folder: the one knot b has
  "$tr" batch m.tsv -o d --merge b 2>err.log || fail "merge into d: $(cat err.log)"
  [ "$(names d/table.tsv | tr '\n' ' ')" = "trefoil " ] || fail "d: $(names d/table.tsv)"
  cmp -s b/trefoil.vect d/trefoil.vect || fail "d's curve is not b's"
  # a record written before the seed and road columns is read with them unknown
  cut -f1-12 d/trefoil.row.tsv >old.tsv && mv old.tsv d/trefoil.row.tsv
  "$tr" batch m.tsv -o d --table-only 2>err.log || fail "old record: $(cat err.log)"
  [ "$(col d/table.tsv trefoil seed) $(col d/table.tsv trefoil road)" = "- -" ] || fail "old record's seed and road"
  # another N is another problem: kept, whatever its length
  sed 's/^hopf\thopf.vect\t-/hopf\thopf.vect\t50/' m.tsv >m50.tsv
  "$tr" batch m50.tsv -o e --only hopf 2>err.log || fail "batch e: $(cat err.log)"
  "$tr" batch m.tsv -o c --merge e --only hopf 2>err.log || fail "merge e: $(cat err.log)"
  grep -q "kept (e's N 100 is not this one's 80)" err.log || fail "N not compared: $(cat err.log)"
  cmp -s a/hopf.vect c/hopf.vect || fail "another N replaced hopf"
  "$tr" batch m.tsv -o c --merge nowhere 2>err.log && fail "merge from a missing folder succeeded"
  grep -q 'no folder nowhere' err.log || fail "missing folder message: $(cat err.log)"
  "$tr" batch m.tsv -o fresh --merge m.tsv 2>err.log && fail "merge from a file succeeded"
  grep -q 'm.tsv is not a folder' err.log || fail "not a folder message: $(cat err.log)"
  [ -e fresh ] && fail "a refused merge made its output folder"
  "$tr" batch m.tsv -o c --merge b -- --seed 2 2>err.log && fail "--merge with tighten options succeeded"
  ;;
retry)
  # --retry R: a knot above its reference is tightened again with the next seeds into OUT/retry-J
  # and the shortest kept; a knot at or below it, or without a reference line, is not retried.
  # The trefoil's reference is 31.0, below the lower bound 31.32 of every nontrivial knot
  # (Denne, Diao and Sullivan 2006), so no road reaches it and both rounds run.
  make_knots - - -
  printf 'knot\tropelength\n3_1\t31.0\nhopf\t1000\n' >ref.tsv
  sed 's/^trefoil\tt23.vect\t-\t--time-limit 3/3_1\tt23.vect\t-\t--time-limit 2 --tries 2/' m.tsv >mr.tsv
  "$tr" batch mr.tsv -o r --compare ref.tsv --retry 2 -- --seed 7 2>err.log || fail "batch --retry: $(cat err.log)"
  for j in 1 2; do
    [ -e r/retry-$j/3_1.row.tsv ] || fail "no retry $j of 3_1: $(ls -R r)"
    [ "$(col r/retry-$j/3_1.row.tsv 3_1 seed)" = $((7 + j)) ] ||
      fail "retry $j's seed: $(cat r/retry-$j/3_1.row.tsv)"
  done
  ls r/retry-*/hopf.* r/retry-*/t25.* >/dev/null 2>&1 && fail "a knot below its reference or without one was retried: $(ls -R r)"
  [ -e r/retry-3 ] && fail "more rounds than --retry 2"
  # the table holds the shortest of the three runs, as measure reads their curves
  best=$(for f in r/retry-1/3_1.vect r/retry-2/3_1.vect; do "$tr" measure "$f" --json | grep -o '"ropelength": [^,]*' | head -1 | cut -d' ' -f2; done |
    sort -g | head -1)
  rl=$(col r/table.tsv 3_1 ropelength)
  awk -v a="$rl" -v b="$best" 'BEGIN { exit !(a <= b * (1 + 1e-9)) }' || fail "table 3_1 $rl, a retry measured $best"
  # (a tie keeps the knot's own run: under the sanitizers a 2 s run of
  # every round can end at the same state; the table prints 10 decimals)
  cmp -s r/3_1.vect r/retry-1/3_1.vect || cmp -s r/3_1.vect r/retry-2/3_1.vect ||
    awk -v a="$rl" -v b="$best" 'BEGIN { exit !(a <= b * (1 + 1e-9)) }' || fail "3_1's curve is none of the runs'"
  # started again: nothing runs, the table is the same
  cp r/table.tsv retry.before
  "$tr" batch mr.tsv -o r --compare ref.tsv --retry 2 -- --seed 7 2>err.log || fail "again: $(cat err.log)"
  grep -q 'tightening' err.log && fail "a knot or a retry ran twice: $(cat err.log)"
  cmp -s retry.before r/table.tsv || fail "the table changed when started again"
  # a round lost (killed before its record): only that round runs again
  rm r/retry-2/3_1.row.tsv
  "$tr" batch mr.tsv -o r --compare ref.tsv --retry 2 -- --seed 7 2>err.log || fail "round 2 again: $(cat err.log)"
  [ "$(grep -c 'retry [0-9] of 2' err.log)" = 1 ] && grep -q 'retry 2 of 2, seed 9' err.log || fail "rerun: $(cat err.log)"
  # --retry-options: the retries' own tighten options, after the knot's. Seen in the steps
  # column of runs bounded by --steps, which every road reaches whatever the machine's speed
  # (the tries column counts the roads that ran: under the sanitizers a 2 s limit once ended
  # after the first of --tries 2, and a road moved from a 30-step result can be skipped)
  sed 's/--time-limit 2 --tries 2/--steps 30/' mr.tsv >ms.tsv
  "$tr" batch ms.tsv -o ro --only 3_1 --compare ref.tsv --retry 1 --retry-options "--steps 20" -- --seed 7 2>err.log ||
    fail "--retry-options: $(cat err.log)"
  [ "$(col ro/table.tsv 3_1 steps)" = 30 ] || fail "the knot's own run: steps $(col ro/table.tsv 3_1 steps)"
  [ "$(col ro/retry-1/3_1.row.tsv 3_1 steps)" = 20 ] ||
    fail "the retry did not take --retry-options: $(cat ro/retry-1/3_1.row.tsv)"
  # given twice: round r takes the ((r - 1) mod 2 + 1)-th (20, 25, then 20 again)
  "$tr" batch ms.tsv -o ro2 --only 3_1 --compare ref.tsv --retry 3 --retry-options "--steps 20" \
    --retry-options "--steps 25" -- --seed 7 2>err.log || fail "two --retry-options: $(cat err.log)"
  for j in 1 2 3; do
    want=$(( j == 2 ? 25 : 20 ))
    [ "$(col ro2/retry-$j/3_1.row.tsv 3_1 steps)" = $want ] ||
      fail "retry $j did not take recipe $(( (j - 1) % 2 + 1 )): $(cat ro2/retry-$j/3_1.row.tsv)"
  done
  grep -q 'retry 2 of 3, seed 9, --steps 25 (' err.log || fail "round 2's progress line: $(cat err.log)"
  args=""
  for j in 1 2 3 4 5 6 7 8 9; do args="$args --retry-options --tries=1"; done
  "$tr" batch mr.tsv -o r9 --compare ref.tsv --retry 1 $args 2>err.log && fail "nine --retry-options succeeded"
  grep -q 'at most 8' err.log || fail "nine --retry-options message: $(cat err.log)"
  "$tr" batch mr.tsv -o r3 --compare ref.tsv --retry-options "--tries 1" 2>err.log && fail "--retry-options without --retry succeeded"
  "$tr" batch mr.tsv -o r3 --compare ref.tsv --retry 1 --retry-options "--tries 1 -o x.vect" 2>err.log &&
    fail "a reserved option in --retry-options succeeded"
  grep -q -- '--retry-options -o' err.log || fail "reserved option message: $(cat err.log)"
  [ -e r3 ] && fail "a refused batch made its output folder"
  "$tr" batch mr.tsv -o r2 --retry 1 2>err.log && fail "--retry without --compare succeeded"
  grep -q -- '--retry needs --compare' err.log || fail "message: $(cat err.log)"
  [ -e r2 ] && fail "a refused batch made its output folder"
  ;;
parallel)
  # The GNU parallel route, for real: one job per knot, two at once, into one folder.
  command -v parallel >/dev/null || { echo "GNU parallel not installed (scripts/deps.sh installs it)"; exit 77; }
  make_knots 80 60 120
  "$tr" batch m.tsv --list | parallel --will-cite -j2 "$tr" batch m.tsv -o out --quiet --only {} 2>err.log ||
    fail "parallel: $(cat err.log)"
  check_table out
  ;;
slurm)
  # scripts/slurm_batch.sh: valid bash; outside an array it refuses; run as the tasks of a
  # two-task array (0-1) would run it, it fills the table.
  s=$src/scripts/slurm_batch.sh
  bash -n "$s" || fail "bash -n"
  make_knots 80 60 120
  env -u SLURM_ARRAY_TASK_ID bash "$s" m.tsv out 2>err && fail "ran outside an array"
  grep -q "not a task of a job array" err || fail "message: $(cat err)"
  for id in 3 4; do
    SLURM_ARRAY_TASK_ID=$id SLURM_ARRAY_TASK_MIN=3 SLURM_ARRAY_TASK_COUNT=2 TIGHTROPE=$tr bash "$s" m.tsv out \
      2>>err.log || fail "task $id: $(cat err.log)"
  done
  check_table out
  ;;
manifests)
  # Manifests by name (issue 47), from the repository's own tables alone: bench/names_manifest.sh
  # gives as many knots per crossing number as there are prime knots (OEIS A002863: 1, 1, 2, 3,
  # 7, 21, 49, 165 for 3..10 crossings) and as many links as there are prime links of two or
  # more components (Thistlethwaite's table; MathWorld "Prime Link", OEIS A048952 + A048953 +
  # A087071: 1, 0, 1, 1, 6, 9, 29, 83 for 2..9), and batch --list takes them. The trefoil and
  # the Hopf link tightened by name: their starts made in OUT/starts (nothing beside the
  # manifest) as make makes them; the table's reference is KnotInfo's ropelength as
  # data/knots/knotinfo_knots.tsv gives it and its diff ours - that; each result measures as
  # the table says, above the published lower bound, shorter than its start, its type kept.
  nm=$src/bench/names_manifest.sh
  want=(1 1 2 3 7 21 49 165)
  for c in 3 4 5 6 7 8 9 10; do
    got=$(bash "$nm" knots $c $c | names /dev/stdin | wc -l)
    [ "$got" = "${want[c - 3]}" ] || fail "knots of $c crossings: $got, want ${want[c - 3]}"
  done
  want=(1 0 1 1 6 9 29 83)
  for c in 2 3 4 5 6 7 8 9; do
    got=$(bash "$nm" links $c $c | names /dev/stdin | wc -l)
    [ "$got" = "${want[c - 2]}" ] || fail "links of $c crossings: $got, want ${want[c - 2]}"
  done
  bash "$nm" knots 10 >knots.tsv || fail "knot manifest"
  bash "$nm" links 9 --scale --time-limit 60 >links.tsv || fail "link manifest"
  [ "$(names knots.tsv | wc -l)" = 249 ] || fail "knots to 10 crossings: $(names knots.tsv | wc -l)"
  [ "$(awk -F'\t' '$1 == "10_165" { print $2 "|" $3 "|" $4 }' knots.tsv)" = "knot 10_165|-|--time-limit 300" ] ||
    fail "10_165's line: $(grep '^10_165' knots.tsv)"
  [ "$(awk -F'\t' '$1 == "6.3.2" { print $2 "|" $4 }' links.tsv)" = "link L6a4|--scale --time-limit 60" ] ||
    fail "the Borromean rings' line: $(grep '^6.3.2' links.tsv)"
  for m in knots.tsv links.tsv; do
    "$tr" batch $m --list >names.txt 2>err || fail "batch --list $m: $(cat err)"
    [ "$(cat names.txt)" = "$(names $m)" ] || fail "batch --list $m"
  done
  bash "$nm" knots 11 10 2>err && fail "MIN above MAX accepted"
  bash "$nm" links 10 2>err && fail "links to 10 crossings accepted (LinkInfo's reach 9)"
  # a manifest of names in a folder of its own; its starts are the batch's, in OUT/starts
  mkdir man
  printf '3_1\tknot 3_1\t-\t--time-limit 5\n2.2.1\tlink:L2a1\t128\t--time-limit 5\n' >man/m.tsv
  "$tr" batch man/m.tsv -o out --compare knotinfo 2>err.log || fail "batch by name: $(cat err.log)"
  [ "$(ls -A man)" = m.tsv ] || fail "the batch wrote beside the manifest: $(ls -A man)"
  "$tr" make knot 3_1 -o make31.vect >/dev/null || fail "make knot 3_1"
  cmp -s <(grep -v '^#' make31.vect) <(grep -v '^#' out/starts/3_1.vect) || fail "the batch's 3_1 is not make's"
  [ "$(col out/table.tsv 3_1 source) $(col out/table.tsv 2.2.1 source)" = "knot:3_1 link:L2a1{0}" ] ||
    fail "sources: $(cut -f1,16 out/table.tsv)"
  [ "$(col out/table.tsv 3_1 type_check) $(col out/table.tsv 2.2.1 type_check)" = "kept kept" ] ||
    fail "type checks: $(cut -f1,17 out/table.tsv)"
  [ "$(col out/table.tsv 2.2.1 N)" = 256 ] || fail "the Hopf link's N: $(col out/table.tsv 2.2.1 N)"
  ki=$(awk -F'\t' '/^#/ { next } !h { for (i = 1; i <= NF; i++) if ($i == "ropelength") c = i; h = 1; next }
    $1 == "3_1" { print $c }' "$src/data/knots/knotinfo_knots.tsv")
  rl=$(col out/table.tsv 3_1 ropelength) ref=$(col out/table.tsv 3_1 ref_ropelength)
  d=$(col out/table.tsv 3_1 diff) pct=$(col out/table.tsv 3_1 diff_pct)
  awk -v r="$ref" -v k="$ki" 'BEGIN { exit !(k > 30 && r == k) }' || fail "3_1's reference $ref, KnotInfo's $ki"
  awk -v a="$rl" -v r="$ref" -v d="$d" -v p="$pct" 'BEGIN { exit !(d != "" && (a - r - d) ^ 2 < 1e-18 &&
    (100 * d / r - p) ^ 2 < 1e-8) }' || fail "3_1: ropelength $rl, reference $ref, diff $d ($pct %)"
  [ "$(col out/table.tsv 2.2.1 ref_ropelength)" = - ] || fail "LinkInfo has no ropelength: $(cat out/table.tsv)"
  measured() { "$tr" measure "$1" --json | grep -o '"ropelength": [^,]*' | head -1 | cut -d' ' -f2; }
  for k in 3_1 2.2.1; do
    rl=$(col out/table.tsv $k ropelength) m=$(measured out/$k.vect) m0=$(measured out/starts/$k.vect)
    lo=31.32 # any nontrivial knot (Denne, Diao and Sullivan 2006); the Hopf link 8 pi
    [ $k = 2.2.1 ] && lo=25.1327412
    awk -v a="$rl" -v m="$m" -v s="$m0" -v lo=$lo 'BEGIN { exit !((a - m) ^ 2 < 1e-16 * m * m && a >= lo && a < s) }' ||
      fail "$k: table $rl, measured $m, its start $m0, bound $lo"
  done
  # a file reference for the links (bench/data/link_ropelength.tsv names them as names_manifest.sh)
  "$tr" batch man/m.tsv -o out --table-only --compare "$src/bench/data/link_ropelength.tsv" 2>err.log ||
    fail "--compare FILE: $(cat err.log)"
  [ "$(col out/table.tsv 2.2.1 ref_ropelength)" = 25.1377890395 ] || fail "Hopf reference: $(cat out/table.tsv)"
  # run again, or with the name spelt otherwise: the same starts (a start by name is its
  # name and braid word), done before; another knot under the name is another start
  "$tr" batch man/m.tsv -o out 2>err.log || fail "again: $(cat err.log)"
  [ "$(grep -c 'done before, skipped' err.log)" = 2 ] || fail "not skipped: $(cat err.log)"
  sed 's/knot 3_1/knot:3.1/' man/m.tsv >m2.tsv
  "$tr" batch m2.tsv -o out 2>err.log || fail "respelt: $(cat err.log)"
  [ "$(grep -c 'done before, skipped' err.log)" = 2 ] || fail "knot:3.1 is not knot 3_1: $(cat err.log)"
  sed 's/knot 3_1/knot 4_1/' man/m.tsv >m3.tsv
  "$tr" batch m3.tsv -o out --table-only 2>err.log || fail "4_1 under 3_1's name: $(cat err.log)"
  grep -q '3_1: .*another start than knot:4_1' err.log || fail "another start not said: $(cat err.log)"
  [ -z "$(col out/table.tsv 3_1 N)" ] || fail "4_1 tabulated with 3_1's record"
  # a record of before the source and type_check columns is read with them unknown
  cut -f1-15 out/2.2.1.row.tsv >old.tsv && mv old.tsv out/2.2.1.row.tsv
  "$tr" batch man/m.tsv -o out --table-only 2>err.log || fail "old record: $(cat err.log)"
  [ "$(col out/table.tsv 2.2.1 source) $(col out/table.tsv 2.2.1 type_check)" = "- -" ] ||
    fail "an old record's source and type check: $(cat out/table.tsv)"
  ;;
*) fail "unknown case $case_" ;;
esac
echo ok
