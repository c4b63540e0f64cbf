#!/usr/bin/env bash
# Hostile-user checks of what the commands do to files (issue 45): an output
# that is a device, a FIFO or the program's own stdout is written in place,
# never replaced; analyze never deletes or writes over its input or a file of
# the user's, and writes all of a run's files or none (a full disk, a signal,
# --plots without gnuplot).
# Usage: hostile_files.sh CASE TIGHTROPE WORK_DIR. Exit 0 pass, 1 fail, 77 skipped.
# Every check is a fact about the files (type, device numbers, inode, bytes)
# or the exit status, never a number from our own earlier output. Devices are
# made with mknod (root, as here and in CI; skipped otherwise); the system's
# own /dev/null is never named, so that an old binary cannot replace it.
set -u
. "$(cd "$(dirname "$0")" && pwd)/cli_testlib.sh"
case_=$1 tr=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
# a tmpfs left mounted by a killed run of disk_full
[ -d "$work/mnt" ] && umount "$work/mnt" 2>/dev/null
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  [ -d "$work/mnt" ] && umount "$work/mnt" 2>/dev/null
  true
}
trap cleanup EXIT
# ok CMD...: exits 0
ok() { run "$@"; [ "$rc" = 0 ] || fail "$*: exit $rc: $(cat err)"; }
# reader FIFO FILE: reads FIFO into FILE in the background (its stdout and
# stderr away from ctest's pipe; killed at exit if no writer ever comes)
reader() { timeout 60 cat "$1" >"$2" 2>/dev/null & pids+=($!); rpid=$!; }
# read_by FIFO: waits for the reader of FIFO to finish
read_by() { wait "$rpid" || fail "nothing was written into the FIFO $1"; }
# state DIR: every file of DIR (hidden ones too) with its inode and its bytes' checksum
state() { (cd "$1" && find . -type f -printf '%i %p\n' | sort -k2 | while read -r i p; do echo "$i $p $(cksum <"$p")"; done); }
# mkdev NAME MAJOR MINOR: a character device, or the case is skipped
mkdev() { mknod "$1" c "$2" "$3" 2>/dev/null || { echo "skipped: cannot mknod (not root?)"; exit 77; }; }
# is_dev NAME MAJOR MINOR: NAME is still that character device
is_dev() {
  [ "$(stat -c '%F %t:%T' "$1")" = "character special file $(printf '%x:%x' "$2" "$3")" ] ||
    fail "$1 is now a $(stat -c %F "$1")"
}
# fake_gnuplot DIR: DIR/gnuplot "draws" every PNG its script names (writes
# "old" into it) and succeeds, in no time and whether gnuplot is installed or not
fake_gnuplot() {
  mkdir -p "$1" && cat >"$1/gnuplot" <<'EOS'
#!/bin/sh
sed -n "s/^set output '\(.*\)'$/\1/p" "$1" | while read -r f; do echo old >"$f"; done
EOS
  chmod +x "$1/gnuplot"
}
"$tr" make circle --radius 5 --n 101 -o k.vect >/dev/null 2>&1 || fail "make circle"
trefoil=$here/../../bench/data/trefoil_1600.vect

case $case_ in
fifo_out)
  # Each command's output into a FIFO: the FIFO stays one and its reader gets
  # the whole output (it used to be replaced by a regular file, exit 0).
  mkfifo p p.vect p.ply
  reader p got
  ok "$tr" measure k.vect --struts p
  [ "$(stat -c %F p)" = fifo ] || fail "--struts: p is now a $(stat -c %F p)"
  read_by p
  [ "$(head -1 got)" = "STRUTS " ] && [ "$(sed -n 2p got | wc -w)" = 2 ] || fail "--struts: the reader got $(head -2 got)"
  reader p got
  ok "$tr" measure k.vect --kkt-forces p
  [ "$(stat -c %F p)" = fifo ] || fail "--kkt-forces: p is now a $(stat -c %F p)"
  read_by p
  grep -q '^component,vertex,' got || fail "--kkt-forces: the reader got $(head -2 got)"
  [ "$(grep -c '^0,' got)" = 101 ] || fail "--kkt-forces: not a row per vertex of the 101-gon"
  reader p.vect got
  ok "$tr" tighten k.vect -o p.vect --device reference --steps 1 --quiet
  [ "$(stat -c %F p.vect)" = fifo ] || fail "tighten -o: p.vect is now a $(stat -c %F p.vect)"
  read_by p.vect
  cp got t.vect && ok "$tr" measure t.vect
  reader p.ply got
  ok "$tr" analyze k.vect --out a --mesh p.ply
  [ "$(stat -c %F p.ply)" = fifo ] || fail "--mesh: p.ply is now a $(stat -c %F p.ply)"
  read_by p.ply
  [ "$(head -1 got)" = ply ] && grep -q '^end_header' got || fail "--mesh: the reader got $(head -2 got)"
  [ -s a/summary.json ] || fail "analyze --mesh into a FIFO: no summary"
  ;;
device_out)
  # A character device (a copy of /dev/null: 1, 3) as the output of each
  # command stays that device; a symbolic link to a regular file still has
  # its target replaced and stays a link.
  mkdev n 1 3 && mkdev n.vect 1 3 && mkdev n.ply 1 3
  ok "$tr" measure k.vect --struts n
  is_dev n 1 3
  ok "$tr" measure k.vect --kkt-forces n
  is_dev n 1 3
  ok "$tr" tighten k.vect -o n.vect --device reference --steps 1 --quiet
  is_dev n.vect 1 3
  ok "$tr" analyze k.vect --out a --mesh n.ply
  is_dev n.ply 1 3
  echo old >real.txt && ln -s real.txt link.txt
  ok "$tr" measure k.vect --struts link.txt
  [ -L link.txt ] && [ "$(head -1 real.txt)" = "STRUTS " ] || fail "link.txt: $(stat -c %F link.txt), real.txt: $(head -1 real.txt)"
  ;;
dev_full)
  # A copy of /dev/full (1, 7) takes nothing: every writer fails with exit 2
  # and one line naming it with the system's reason, and the device stays.
  # analyze writes its folder only if the mesh is written too.
  mkdev full 1 7 && mkdev full.vect 1 7 && mkdev full.ply 1 7
  refused 2 "cannot write full: No space left on device" "$tr" measure k.vect --struts full
  is_dev full 1 7
  refused 2 "cannot write full: No space left on device" "$tr" measure k.vect --kkt-forces full
  is_dev full 1 7
  refused 2 "cannot write full.vect: No space left on device" "$tr" tighten k.vect -o full.vect --device reference --steps 1 --quiet
  is_dev full.vect 1 7
  refused 2 "--mesh full.ply: cannot write full.ply: No space left on device" "$tr" analyze k.vect --out a --mesh full.ply
  is_dev full.ply 1 7
  [ -e a ] && fail "the mesh failed, yet the folder a was written: $(ls -A a)"
  # over an earlier run's folder (other numbers under the same names): its
  # files put back as they were, the same inodes with the same bytes
  ok "$tr" analyze k.vect --out b -m 5
  before=$(state b)
  refused 2 "--mesh full.ply: cannot write full.ply: No space left on device" "$tr" analyze k.vect --out b --mesh full.ply
  [ "$(state b)" = "$before" ] || fail "the mesh failed, yet b changed: $(ls -A b)"
  ;;
stdout_out)
  # /dev/stdout as an output is the program's stdout: through a pipe (it
  # used to fail: the link was followed to "pipe:[N]") and appended to a file
  # the shell opened with >> (the file was replaced, its start lost).
  "$tr" measure k.vect --struts /dev/stdout 2>err | cat >got
  [ "${PIPESTATUS[0]}" = 0 ] || fail "into a pipe: exit ${PIPESTATUS[0]}: $(cat err)"
  grep -q '^STRUTS $' got && grep -q 'ropelength' got || fail "into a pipe: $(head -3 got)"
  echo first >log
  "$tr" measure k.vect --struts /dev/stdout >>log 2>err || fail "appended: exit $?: $(cat err)"
  [ "$(head -1 log)" = first ] || fail "the start of log is lost: $(head -1 log)"
  grep -q '^STRUTS $' log && grep -q 'ropelength' log || fail "appended: $(head -3 log)"
  ;;
analyze_input)
  # The input inside the output folder under one of analyze's names: a run
  # that does not write that name leaves it (it used to delete it as stale),
  # a run that would write it is refused with nothing written.
  awk 'NF == 3 && $1 ~ /^[-0-9]/' k.vect >knot.txt
  mkdir d && cp knot.txt d/tube.dat && ino=$(stat -c %i d/tube.dat)
  ok "$tr" analyze d/tube.dat --out d
  [ -f d/tube.dat ] && [ "$(stat -c %i d/tube.dat)" = "$ino" ] && cmp -s d/tube.dat knot.txt || fail "the input d/tube.dat was removed or changed"
  [ -s d/summary.json ] || fail "no summary"
  fake_gnuplot quick
  before=$(state d)
  refused 2 "the output d/tube.dat is the input d/tube.dat" env PATH="$work/quick:$PATH" "$tr" analyze d/tube.dat --out d --plots
  [ "$(state d)" = "$before" ] || fail "a refused run changed d: $(ls -A d)"
  ;;
analyze_user_files)
  # Files and folders of the user's in the output folder are never removed
  # or replaced: a comp0/ of theirs (it used to be emptied of analyze's names
  # and removed), an empty comp1/, a report.txt of theirs, an output they
  # edited; a rerun over an unchanged earlier run is fine.
  mkdir -p d/comp0 d/comp1 && echo mine >d/comp0/report.txt
  ok "$tr" analyze k.vect --out d
  [ "$(cat d/comp0/report.txt)" = mine ] || fail "the user's comp0/report.txt removed"
  [ -d d/comp1 ] || fail "the user's empty comp1/ removed"
  ok "$tr" analyze k.vect --out d
  mkdir e && echo mine >e/report.txt
  refused 2 "will not replace e/report.txt: not a file tightrope analyze wrote" "$tr" analyze k.vect --out e
  [ "$(cat e/report.txt)" = mine ] && [ "$(ls -A e)" = report.txt ] || fail "e changed: $(ls -A e)"
  echo edited >>d/summary.json
  before=$(state d)
  refused 2 "will not replace d/summary.json: .*changed since" "$tr" analyze k.vect --out d
  [ "$(state d)" = "$before" ] || fail "a refused run changed d"
  # a link into d, where comp0/ holds a file of the user's under one of its names
  "$tr" make hopf --n 60 -o h.vect >/dev/null || fail "make hopf"
  refused 2 "will not replace d/comp0/report.txt" "$tr" analyze h.vect --out d
  [ "$(cat d/comp0/report.txt)" = mine ] || fail "the user's comp0/report.txt replaced"
  ;;
no_gnuplot)
  # --plots without gnuplot on PATH fails before anything is read or
  # computed (a missing input is not even opened), and writes nothing; it
  # used to write the tables and exit 0.
  mkdir empty
  refused 2 "--plots needs gnuplot, which is not on PATH" env PATH="$work/empty" "$tr" analyze no_such.vect --out o --plots
  refused 2 "--plots needs gnuplot, which is not on PATH" env PATH="$work/empty" "$tr" analyze k.vect --out o --plots
  [ -e o ] && fail "o written: $(ls -A o)"
  ;;
plots_signal)
  # SIGTERM or SIGINT while gnuplot draws: the gnuplot is stopped (not left
  # running), no temporary is left, the folder is as it was (a new one is
  # not left at all), and analyze ends by that signal. A fake gnuplot
  # records its pid and waits; another one "draws" each PNG and succeeds.
  mkdir bin
  cat >bin/gnuplot <<EOS
#!/bin/sh
echo \$\$ >"$work/gnuplot.pid"
exec sleep 60
EOS
  chmod +x bin/gnuplot
  fake_gnuplot quick
  ok env PATH="$work/quick:$PATH" "$tr" analyze k.vect --out d --plots
  [ "$(cat d/curvature_torsion.png)" = old ] || fail "the quick fake drew nothing"
  before=$(state d)
  for sig in TERM INT; do
    out=d
    [ $sig = INT ] && out=e
    rm -f gnuplot.pid
    PATH="$work/bin:$PATH" "$tr" analyze k.vect --out $out --plots >/dev/null 2>err$sig &
    tpid=$!
    pids+=($tpid)
    for _ in $(seq 300); do [ -s gnuplot.pid ] && break; sleep 0.1; done
    [ -s gnuplot.pid ] || fail "$sig: gnuplot never started: $(cat err$sig)"
    kill -$sig $tpid
    wait $tpid
    rc=$?
    gp=$(cat gnuplot.pid)
    sleep 0.2
    kill -0 "$gp" 2>/dev/null && { kill "$gp"; fail "$sig: gnuplot $gp still running after analyze ended"; }
    [ $rc = $((128 + $(kill -l $sig))) ] || fail "$sig: exit $rc, want death by SIG$sig: $(cat err$sig)"
    grep -q "interrupted; nothing written to $out" err$sig || fail "$sig: $(cat err$sig)"
    left=$(find . -name '*.tmp*' -o -name '.tr*')
    [ -z "$left" ] || fail "$sig: temporaries left: $left"
  done
  [ "$(state d)" = "$before" ] || fail "SIGTERM: d changed: $(ls -A d)"
  [ -e e ] && fail "SIGINT: the new folder e left: $(ls -A e)"
  true
  ;;
disk_full)
  # A disk that fills during analyze: all of a run's files or none. On a
  # tmpfs half the size of the run's output (or, where no tmpfs can be
  # mounted, a file size limit of half its largest file): a new folder is
  # not left at all, an earlier run's folder is left exactly as it was
  # (each file's inode and bytes). It used to leave 4 of 9 files.
  [ -f "$trefoil" ] || fail "no $trefoil"
  ok "$tr" analyze "$trefoil" --out ref
  mkdir mnt
  limited=()
  if mount -t tmpfs -o size="$(( $(du -sk ref | cut -f1) / 2 ))k" tmpfs mnt 2>/dev/null; then
    why="No space left on device"
  else
    big=$(find ref -type f -printf '%s\n' | sort -n | tail -1)
    limited=(bash -c 'trap "" XFSZ; ulimit -f "$1" && shift && exec "$@"' limit $((big / 2048)))
    why="File too large"
  fi
  refused 2 "cannot write mnt/a/[a-z_]+\.[a-z]+: $why" "${limited[@]}" "$tr" analyze "$trefoil" --out mnt/a
  [ -e mnt/a ] && fail "a failed run left mnt/a: $(ls -A mnt/a)"
  ok "$tr" analyze k.vect --out mnt/b
  before=$(state mnt/b)
  refused 2 "cannot write mnt/b/[a-z_]+\.[a-z]+: $why" "${limited[@]}" "$tr" analyze "$trefoil" --out mnt/b
  [ "$(state mnt/b)" = "$before" ] || fail "a failed run changed mnt/b: $(ls -A mnt/b)"
  [ -z "$(find mnt -name '.tr*')" ] || fail "temporaries left: $(find mnt -name '.tr*')"
  ;;
*) fail "unknown case $case_" ;;
esac
exit 0
