#!/usr/bin/env bash
# Hostile-user checks of the command line (issue 22): inputs that are accepted
# but wrong, outputs that would destroy inputs, messages that point elsewhere.
# Usage: hostile_cli.sh CASE TIGHTROPE WORK_DIR. Exit 0 pass, 1 fail, 77 skipped.
# Expected numbers are closed forms (a regular n-gon: ropelength 2n tan(pi/n),
# length 2nR sin(pi/n)) or facts about the files (inode, mode), never our own
# earlier output.
set -u
. "$(cd "$(dirname "$0")" && pwd)/cli_testlib.sh"
case_=$1 tr=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
# scaled FACTOR IN OUT: a VECT file with every vertex multiplied by FACTOR
scaled() {
  awk -v f="$1" '/^#/ || NR <= 5 || NF != 3 { print; next } { printf "%.17g %.17g %.17g\n", $1 * f, $2 * f, $3 * f }' "$2" >"$3"
}

case $case_ in
scale)
  # A regular 101-gon of circumradius 5, times 1e-300 and 1e300: ropelength
  # 2n tan(pi/n) whatever the scale, length 2nR sin(pi/n) in the file's units.
  "$tr" make circle --radius 5 --n 101 -o c.vect >/dev/null || fail "make"
  want=$(awk 'BEGIN { n = 101; pi = atan2(0, -1); printf "%.17g", 2 * n * sin(pi / n) / cos(pi / n) }')
  for f in 1e-300 1e300; do
    scaled $f c.vect s$f.vect
    run "$tr" measure --json --kkt s$f.vect
    [ "$rc" = 0 ] || fail "measure x$f: exit $rc: $(cat err)"
    rl=$(json_get ropelength out) len=$(json_get length out) res=$(json_get residual out)
    rel "$rl" "$want" 1e-12 || fail "x$f: ropelength $rl, want $want"
    rel "$len" "$(awk -v f=$f 'BEGIN { n = 101; pi = atan2(0, -1); printf "%.17g", 2 * n * 5 * sin(pi / n) * f }')" 1e-12 ||
      fail "x$f: length $len"
    awk -v r="$res" 'BEGIN { exit !(r < 1e-10) }' || fail "x$f: KKT residual $res (a regular polygon is critical)"
    # tighten refuses it in its own units, naming --scale, and tightens it with --scale
    refused 2 "s$f.vect has thickness [0-9.e+-]+, too far from 1.*--scale" "$tr" tighten s$f.vect -o t.vect --device reference
    [ -e t.vect ] && fail "x$f: refused, yet t.vect written"
    run "$tr" tighten --scale s$f.vect -o t$f.vect --device reference --steps 1 --quiet
    [ "$rc" = 0 ] || fail "tighten --scale x$f: exit $rc: $(cat err)"
    run "$tr" measure --json t$f.vect
    th=$(json_get thickness out)
    rel "$th" 1 1e-9 || fail "tighten --scale x$f: thickness $th, want 1"
  done
  # analyze scales to thickness 1 itself; --no-scale at 1e-300 is refused
  run "$tr" analyze s1e-300.vect --out a
  [ "$rc" = 0 ] || fail "analyze x1e-300: exit $rc: $(cat err)"
  grep -q "^  thickness 1, ropelength ${want:0:6}" out || fail "analyze x1e-300: $(head -3 out)"
  refused 2 "thickness [0-9.]+e-300, too far from 1.*drop --no-scale" "$tr" analyze s1e-300.vect --out b --no-scale
  [ -e b ] && fail "analyze --no-scale refused, yet b written"
  ;;
crossing)
  # A figure eight through the origin (vertex 0 and, to rounding, vertex 32)
  # and one whose two strands meet at an exactly shared point: no thickness.
  awk 'BEGIN { pi = atan2(0, -1); for (i = 0; i < 64; i++) { t = 2 * pi * i / 64
       printf "%.17g %.17g 0\n", 3 * sin(t), 3 * sin(t) * cos(t) } }' >eight.txt
  awk 'NR == 33 { print "0 0 0"; next } { print }' eight.txt >exact.txt
  for f in eight.txt exact.txt; do
    for cmd in "measure" "measure --kkt" "tighten -o o.vect --device reference" "tighten --scale -o o.vect --device reference" "analyze --out a"; do
      refused 2 "$f: .*passes through itself: the edge from vertex [0-9]+ to [0-9]+ of component 0 meets" "$tr" $cmd $f
    done
    [ -e o.vect ] || [ -e a ] && fail "$f: refused, yet an output was written"
  done
  ;;
same_file)
  # An output that is one of the inputs, by identity: refused before anything
  # is written, and the input is left as it was.
  "$tr" make circle --radius 5 --n 101 -o k.vect >/dev/null || fail "make"
  cp k.vect orig.vect
  ln k.vect hard.vect
  ln -s k.vect sym.vect
  mkdir d && ln -s ../k.vect d/up.vect
  for o in k.vect ./k.vect hard.vect sym.vect d/up.vect "$work/k.vect"; do
    refused 2 "--struts $o is the input k.vect" "$tr" measure k.vect --struts "$o"
    refused 2 "--kkt-forces $o is the input k.vect" "$tr" measure k.vect --kkt-forces "$o"
    refused 2 "the output $o is the input k.vect" "$tr" tighten k.vect -o "$o" --device reference
  done
  refused 2 "--struts and --kkt-forces are both s.txt" "$tr" measure k.vect --struts s.txt --kkt-forces s.txt
  cmp -s k.vect orig.vect || fail "k.vect changed"
  [ -L sym.vect ] && [ -L d/up.vect ] || fail "a link was replaced"
  [ -e s.txt ] && fail "s.txt written"
  ;;
overwrite)
  # Overwriting keeps the output's mode, writes through a symbolic link to
  # its target (also a target that does not exist yet), takes a legal name
  # of 250 characters, and leaves no temporary behind.
  "$tr" make circle --radius 5 --n 101 -o k.vect >/dev/null || fail "make"
  echo old >s600.txt && chmod 600 s600.txt
  echo old >s640.txt && chmod 640 s640.txt
  echo old >real.txt && ln -s real.txt link.txt
  mkdir sub && ln -s sub/new.txt dangling.txt
  for o in s600.txt s640.txt link.txt dangling.txt; do
    run "$tr" measure k.vect --struts $o
    [ "$rc" = 0 ] || fail "--struts $o: exit $rc: $(cat err)"
  done
  [ "$(stat -c %a s600.txt)" = 600 ] || fail "s600.txt now $(stat -c %a s600.txt)"
  [ "$(stat -c %a s640.txt)" = 640 ] || fail "s640.txt now $(stat -c %a s640.txt)"
  [ -L link.txt ] || fail "link.txt replaced by a plain file"
  [ "$(head -1 real.txt)" = "STRUTS " ] || fail "real.txt not written: $(head -1 real.txt)"
  [ -L dangling.txt ] && [ "$(head -1 sub/new.txt)" = "STRUTS " ] || fail "dangling.txt: its target not written"
  # the longest name this file system takes (NAME_MAX, 255 on Linux) less 5
  long=$(printf "%0$(( $(getconf NAME_MAX .) - 5 ))d" 0 | tr 0 a).vect
  [ ${#long} -gt 200 ] || fail "name of ${#long}"
  run "$tr" make circle -o "$long"
  [ "$rc" = 0 ] && [ -s "$long" ] || fail "make -o (${#long} characters): exit $rc: $(cat err)"
  run "$tr" measure "$long" --struts "${long%.vect}.txt"
  [ "$rc" = 0 ] || fail "--struts (${#long} characters): exit $rc: $(cat err)"
  leftover=$(ls -A . sub | grep -E '^\.tr\.|\.tmp')
  [ -z "$leftover" ] || fail "temporaries left: $leftover"
  ;;
vect_line)
  # A number missing from, or added to, line 8 of a VECT file (tests/bad,
  # one vertex to a line) is reported at line 8, not where the count ends.
  bad=$here/../bad
  refused 2 "vect_missing_number.vect:8: 2 numbers on the line of vertex 2" "$tr" measure "$bad/vect_missing_number.vect"
  refused 2 "vect_extra_number.vect:8: more than 3 numbers on the line of vertex 2" "$tr" measure "$bad/vect_extra_number.vect"
  # vertices several to a line throughout are still read (VECT is a stream)
  printf 'VECT\n1 4 0\n-4\n0\n0 0 0 4 0 0\n4 4 0 0 4 0\n' >square.vect
  run "$tr" measure --json square.vect
  [ "$rc" = 0 ] && [ "$(json_get length out)" = 16 ] || fail "square, two vertices to a line: $(cat out err)"
  ;;
make_refuse)
  # make writes no start that tighten refuses: a circle of radius 0.5 (MinRad
  # R cos(pi/n) < 1/2), of 3 vertices (edges 2R sin(pi/3) = 5.2 > 1), of
  # radius 2 and 12 vertices (edges 4 sin(pi/12) = 1.035 > 1); radius 2 with
  # 13 vertices (edges 0.964) is written and tighten takes it.
  refused 2 "radius 0.5, 64 vertices: tighten would refuse it: .*MinRad 0.499" "$tr" make circle --radius 0.5 -o a.vect
  refused 2 "3 vertices: tighten would refuse it: .*edges of length 5.2" "$tr" make circle --n 3 -o b.vect
  refused 2 "12 vertices: tighten would refuse it: .*edges of length 1.04" "$tr" make circle --radius 2 --n 12 -o c.vect
  [ -e a.vect ] || [ -e b.vect ] || [ -e c.vect ] && fail "a refused start was written"
  run "$tr" make circle --radius 2 --n 13 -o d.vect
  [ "$rc" = 0 ] || fail "radius 2, 13 vertices: exit $rc: $(cat err)"
  run "$tr" tighten d.vect -o e.vect --device reference --steps 1 --quiet
  [ "$rc" = 0 ] || fail "tighten of make's circle: exit $rc: $(cat err)"
  ;;
args)
  # Options: a bad count states the valid range, contradicting or repeated
  # options are an error, --refine-to below the start's N is an error.
  "$tr" make circle -o k.vect >/dev/null || fail "make"
  refused 2 "bad --n '3' \\(an integer >= 4, vertices per component\\)" "$tr" tighten k.vect -o o.vect --n 3
  refused 2 "bad --n '2' \\(a vertex count, an integer from 3 to" "$tr" make circle --n 2 -o o.vect
  refused 2 "--kkt and --no-kkt contradict" "$tr" tighten k.vect -o o.vect --kkt --no-kkt
  refused 2 "--kkt and --no-kkt contradict" "$tr" tighten k.vect -o o.vect --no-kkt --kkt
  refused 2 "-o given twice" "$tr" tighten k.vect -o o.vect -o p.vect
  refused 2 "--paper and --no-paper contradict" "$tr" analyze k.vect --out a --paper --no-paper
  refused 2 "--refine-to 32 is below the 64 vertices of component 0" "$tr" tighten k.vect -o o.vect --refine-to 32 --device reference
  refused 2 "bad --radius '0x10'" "$tr" make circle --radius 0x10 -o o.vect
  [ -e o.vect ] || [ -e p.vect ] || [ -e a ] && fail "an output was written"
  ;;
open_ends)
  # The clasp with its constraint comments is taken; the same ropes without
  # them (free ends), or with one end held, are refused naming the comments.
  "$tr" make clasp --n 60 -o clasp.vect >/dev/null || fail "make clasp"
  sed -e '/^# Constraint/d' -e 's/ *# Cst: [0-9]*//' clasp.vect >free.vect
  awk '/# Cst: 2/ && !done { sub(/ *# Cst: 2/, ""); done = 1 } { print }' clasp.vect >half.vect
  grep -c 'Cst:' half.vect | grep -qx 3 || fail "half.vect: $(grep -c 'Cst:' half.vect) held ends, want 3"
  run "$tr" measure free.vect
  [ "$rc" = 0 ] || fail "free.vect is a valid file: $(cat err)"
  refused 2 "free.vect: component 0 is open and its first end \\(vertex 0\\) is free.*# Constraint.*# Cst:" \
    "$tr" tighten free.vect -o o.vect --device reference
  refused 2 "half.vect: component 1 is open and its (first|last) end .* is free" "$tr" tighten half.vect -o o.vect --device reference
  [ -e o.vect ] && fail "refused, yet o.vect written"
  run "$tr" tighten clasp.vect -o o.vect --device reference --steps 1 --quiet
  [ "$rc" = 0 ] || fail "the held clasp: exit $rc: $(cat err)"
  ;;
dev_zero)
  # Reading allocates what the file holds: /dev/zero (endless NUL bytes) is
  # refused at its first byte under a 1 GB address-space limit (it used to
  # take 4.2 GB first); endless text runs out of memory, which is exit 1.
  # (A sanitizer build reserves more address space than any such limit.)
  bash -c 'ulimit -v 1000000 && exec "$0" --help' "$tr" >/dev/null 2>&1 || { echo "skipped: cannot run under ulimit -v"; exit 77; }
  refused 2 "/dev/zero:1: a NUL byte at offset 0: not a text file" bash -c 'ulimit -v 1000000 && exec "$0" measure /dev/zero' "$tr"
  refused 1 "out of memory reading /dev/stdin" bash -c 'yes "0 0 0" | (ulimit -v 300000 && exec "$0" measure /dev/stdin)' "$tr"
  ;;
devices)
  # A device whose driver cannot build the kernels (here: a syntax error in
  # tension.cl through TIGHTROPE_KERNEL_DIR) is not usable: 'devices' says
  # why, '--device opencl' fails with the reason and 'auto' falls back to
  # the reference naming it.
  "$tr" devices --json >dev.json 2>/dev/null || fail "devices: exit $?"
  grep -q '"usable": true, "reason": null}' dev.json && grep -q '"id": "[0-9]*:[0-9]*"' dev.json ||
    { echo "skipped: no usable opencl device here"; exit 77; }
  cp -r "$here/../../kernels" k && echo 'this is not opencl c;' >>k/tension.cl
  export TIGHTROPE_KERNEL_DIR=$work/k
  "$tr" devices >list 2>/dev/null || fail "devices with broken kernels: exit $?"
  grep -q 'UNUSABLE: the kernels do not build' list || fail "devices: $(cat list)"
  "$tr" devices --json >dev2.json 2>/dev/null
  [ "$(grep -o '"usable": true' dev2.json | wc -l)" = 1 ] || fail "an opencl device still usable: $(cat dev2.json)"
  "$tr" make circle -o c.vect >/dev/null
  run "$tr" tighten c.vect -o o.vect --device opencl --steps 1 --quiet
  [ "$rc" = 1 ] && grep -q 'no usable opencl device (the kernels do not build' err || fail "--device opencl: exit $rc: $(cat err)"
  [ -e o.vect ] && fail "--device opencl failed, yet o.vect written"
  run "$tr" tighten c.vect -o o.vect --device auto --steps 1 --quiet
  [ "$rc" = 0 ] && grep -q 'warning: using the serial reference.*the kernels do not build' err || fail "--device auto: exit $rc: $(cat err)"
  ;;
analyze_stale)
  # analyze into a folder holding an earlier run: the tight trefoil has
  # contacts (sigma.csv, fixed_points.csv), a circle has none; after the
  # circle those files are gone, and a file of the user's stays.
  knot=$here/../data/tightknot/3_1.vect
  [ -f "$knot" ] || fail "no $knot"
  run "$tr" analyze "$knot" --out a
  [ "$rc" = 0 ] && [ -s a/sigma.csv ] && [ -s a/fixed_points.csv ] || fail "trefoil: exit $rc, $(ls a)"
  echo mine >a/notes.txt
  "$tr" make circle -o c.vect >/dev/null
  run "$tr" analyze c.vect --out a
  [ "$rc" = 0 ] || fail "circle: exit $rc: $(cat err)"
  [ -e a/sigma.csv ] || [ -e a/fixed_points.csv ] && fail "stale files left: $(ls a)"
  [ "$(cat a/notes.txt)" = mine ] || fail "notes.txt removed"
  grep -q '"file": ".*c.vect"' a/summary.json || grep -q 'c.vect' a/summary.json || fail "summary.json not the circle's"
  ;;
analyze_layout)
  # a knot into a folder that holds an earlier link's comp0/ comp1/, and a
  # link into one that holds a knot's files: the other layout's files of
  # ours go (a comp folder left empty too), a file of the user's stays.
  "$tr" make hopf --n 60 -o h.vect >/dev/null && "$tr" make circle -o c.vect >/dev/null || fail "make"
  run "$tr" analyze h.vect --out a
  [ "$rc" = 0 ] && [ -s a/comp0/curvature.csv ] && [ -s a/comp1/summary.json ] || fail "hopf: exit $rc, $(ls -R a)"
  echo mine >a/comp1/notes.txt
  run "$tr" analyze c.vect --out a
  [ "$rc" = 0 ] && [ -s a/summary.json ] || fail "circle: exit $rc: $(cat err)"
  [ -e a/comp0 ] && fail "comp0 left: $(ls -R a)"
  [ -e a/comp1/curvature.csv ] || [ -e a/comp1/summary.json ] && fail "comp1's files left: $(ls -R a)"
  [ "$(cat a/comp1/notes.txt)" = mine ] || fail "the user's comp1/notes.txt removed"
  echo mine >a/notes.txt
  run "$tr" analyze h.vect --out a
  [ "$rc" = 0 ] && [ -s a/comp0/summary.json ] || fail "hopf again: exit $rc"
  for f in curvature.csv torsion.csv summary.json report.txt; do
    [ -e "a/$f" ] && fail "the knot's $f left beside the link's comp folders: $(ls a)"
  done
  [ "$(cat a/notes.txt)" = mine ] || fail "the user's notes.txt removed"
  ;;
*) fail "unknown case $case_" ;;
esac
exit 0
