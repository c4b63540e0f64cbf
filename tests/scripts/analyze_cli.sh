#!/usr/bin/env bash
# CLI checks of 'tightrope analyze'. Usage: analyze_cli.sh CASE TIGHTROPE DATA_DIR WORK_DIR
# (DATA_DIR: tests/data, which holds TightKnot's N = 400 trefoil)
# Exit 0 pass, 1 fail, 77 skipped. The 'cycles' case takes the knot file as a 5th argument.
set -u
case_=$1 tr=$2 data=$3 work=$4
set -- "$@" ''
knot=$data/tightknot/3_1.vect
# the cases that analyze the TightKnot trefoil fail loudly if the repository lost it
need_knot() { [ -f "$knot" ] || fail "no $knot"; }
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
case $case_ in
trefoil)
  need_knot
  # The tight trefoil (N = 400) is D3-symmetric; every table and the summary are written.
  "$tr" analyze "$knot" --out "$work/out" -m 1 >"$work/stdout" 2>"$work/stderr" || fail "exit $?: $(cat "$work/stderr")"
  for f in curvature.csv torsion.csv plateaus.csv symmetry.csv contacts.csv summary.json report.txt; do
    [ -s "$work/out/$f" ] || fail "missing $f"
  done
  grep -q '"verdict": "D3"' "$work/out/summary.json" || fail "not D3: $(grep verdict "$work/out/summary.json")"
  # one row per arc (m = 1: 400 vertices) after the comment and the header
  [ "$(grep -vc '^#' "$work/out/curvature.csv")" = 401 ] || fail "curvature.csv rows"
  grep -q '^symmetry: D3' "$work/stdout" || fail "report"
  ;;
no_gnuplot)
  need_knot
  # Without gnuplot, --plots fails at once: exit 2, one line saying gnuplot is needed,
  # nothing written (it used to write the CSV files alone and exit 0; issue 45).
  PATH=/nonexistent "$tr" analyze "$knot" --out "$work/out" -m 2 --plots >"$work/stdout" 2>"$work/stderr"; rc=$?
  [ $rc = 2 ] || fail "exit $rc"
  grep -q '^tightrope analyze: --plots needs gnuplot' "$work/stderr" || fail "no message: $(cat "$work/stderr")"
  [ "$(wc -l <"$work/stderr")" = 1 ] || fail "not one line: $(cat "$work/stderr")"
  [ -e "$work/out" ] && fail "written without gnuplot: $(ls "$work/out")"
  ;;
plots)
  need_knot
  command -v gnuplot >/dev/null || { echo "gnuplot not installed"; exit 77; }
  "$tr" analyze "$knot" --out "$work/out" -m 1 --plots >"$work/stdout" 2>"$work/stderr" || fail "exit $?: $(cat "$work/stderr")"
  for f in curvature_torsion plateau_zoom accumulated_torsion; do
    [ -s "$work/out/$f.png" ] || fail "missing $f.png"
    [ "$(head -c 4 "$work/out/$f.png" | od -An -c | tr -d ' ')" = '211PNG' ] || fail "$f.png is not a PNG"
  done
  ;;
plots_coarse)
  # Coarse knots (N = 100 and 400, m = 10: averaged arcs of 3.3 and 1.0) have no kappa = 1
  # plateau and few points: every plot must still be drawn and hold data (the zoom was once
  # fixed to [0, 0.6], empty there, and gnuplot failed), and no temporary file is left.
  # -m 10 explicitly: the default now follows N (m = 1 here) and would not leave few points.
  command -v gnuplot >/dev/null || { echo "gnuplot not installed"; exit 77; }
  for n in 100 400; do
    "$tr" make torus 2 3 --n $n -o "$work/t$n.vect" >/dev/null 2>&1 || fail "make N = $n"
    "$tr" analyze "$work/t$n.vect" --out "$work/o$n" -m 10 --plots >"$work/stdout" 2>"$work/stderr" || fail "N = $n: exit $?: $(cat "$work/stderr")"
    for f in curvature_torsion plateau_zoom accumulated_torsion; do
      [ "$(head -c 4 "$work/o$n/$f.png" | od -An -c | tr -d ' ')" = '211PNG' ] || fail "N = $n: $f.png is not a PNG"
    done
    # gnuplot says so when a plot has no data in its range
    grep -Ei 'undefined|empty|no valid points' "$work/o$n/gnuplot.log" && fail "N = $n: a plot without data"
    ls -a "$work/o$n" | grep -q '\.tmp' && fail "N = $n: temporary files left: $(ls -a "$work/o$n")"
    grep -q "set xrange \[Z0:Z1\]" "$work/o$n/plots.gp" || fail "N = $n: no zoom window"
  done
  ;;
plots_origin)
  # A stadium (two unit semicircles joined by straights of length 3, N = 400) has C2 symmetry
  # and the origin at a semicircle apex, in the middle of a kappa = 1 plateau whose ends lie
  # pi/2 before and after it: the zoom window must run across the origin, from below -pi/2 to
  # above pi/2, and be a zoom (under 3/4 of L), not run from l1 ~ L - pi/2 down to l2 (a
  # reversed axis showing the rest of the curve).
  command -v gnuplot >/dev/null || { echo "gnuplot not installed"; exit 77; }
  awk 'BEGIN { pi = atan2(0, -1); s = 3; L = 2 * pi + 2 * s; n = 400
    for (i = 0; i < n; i++) { t = 1.234 + i * L / n; t -= L * int(t / L)
      if (t < pi / 2) { x = s / 2 + cos(t); y = sin(t) }
      else if (t < pi / 2 + s) { x = s / 2 - (t - pi / 2); y = 1 }
      else if (t < 3 * pi / 2 + s) { a = pi / 2 + t - pi / 2 - s; x = -s / 2 + cos(a); y = sin(a) }
      else if (t < 3 * pi / 2 + 2 * s) { x = -s / 2 + (t - 3 * pi / 2 - s); y = -1 }
      else { a = 3 * pi / 2 + t - 3 * pi / 2 - 2 * s; x = s / 2 + cos(a); y = sin(a) }
      printf "%.17g %.17g 0\n", x, y } }' >"$work/stadium.txt"
  "$tr" analyze "$work/stadium.txt" --out "$work/o" --no-scale -m 2 --plots >"$work/stdout" 2>"$work/stderr" || fail "exit $?: $(cat "$work/stderr")"
  grep -q '^symmetry: C2' "$work/stdout" || fail "not C2: $(grep symmetry "$work/stdout")"
  # (a plane curve: tau = 0 throughout, which gnuplot calls an empty y range)
  grep -Ei 'undefined|no valid points' "$work/o/gnuplot.log" && fail "a plot without data"
  awk -F'[=;]' '/^Z0 = / { z0 = $2 + 0; z1 = $4 + 0; pi = atan2(0, -1)
    ok = z0 < -pi / 2 && z1 > pi / 2 && z1 - z0 < 0.75 * (2 * pi + 6) }
    END { exit !ok }' "$work/o/plots.gp" || fail "zoom window: $(grep '^Z0' "$work/o/plots.gp")"
  ;;
plots_atomic)
  need_knot
  # PNGs are drawn under temporary names and put in place only when gnuplot succeeds: a
  # gnuplot that fails half-way leaves the previous run's PNGs whole and no temporary file
  # behind. The fake gnuplot writes $GP_WRITES into every file named by a 'set output' line
  # of plots.gp, then exits with $GP_EXIT.
  mkdir -p "$work/bin"
  cat >"$work/bin/gnuplot" <<'EOS'
#!/bin/sh
sed -n "s/^set output '\(.*\)'$/\1/p" "$1" | while read -r f; do echo "$GP_WRITES" >"$f"; done
exit "$GP_EXIT"
EOS
  chmod +x "$work/bin/gnuplot"
  GP_WRITES=old GP_EXIT=0 PATH="$work/bin:$PATH" "$tr" analyze "$knot" --out "$work/out" -m 2 --plots >/dev/null 2>"$work/err" ||
    fail "the first run: exit $?: $(cat "$work/err")"
  pngs=$(ls "$work/out"/*.png)
  GP_WRITES=partial GP_EXIT=1 PATH="$work/bin:$PATH" "$tr" analyze "$knot" --out "$work/out" -m 2 --plots >/dev/null 2>"$work/err"; rc=$?
  [ $rc = 1 ] || fail "failing gnuplot: exit $rc"
  grep -q '^tightrope analyze: plots: gnuplot failed' "$work/err" || fail "message: $(cat "$work/err")"
  [ "$(ls "$work/out"/*.png)" = "$pngs" ] || fail "the PNGs changed: $(ls "$work/out")"
  for f in $pngs; do [ "$(cat "$f")" = old ] || fail "$f overwritten by a failed run"; done
  ls -a "$work/out" | grep -q '\.png.\|^\.tr' && fail "temporary files left: $(ls -a "$work/out")"
  # the same fake, succeeding: each PNG takes its final name
  GP_WRITES=partial GP_EXIT=0 PATH="$work/bin:$PATH" "$tr" analyze "$knot" --out "$work/out" -m 2 --plots >/dev/null 2>"$work/err" || fail "exit $?: $(cat "$work/err")"
  for f in curvature_torsion plateau_zoom accumulated_torsion contact_map sigma9; do
    [ "$(cat "$work/out/$f.png")" = partial ] || fail "$f.png not renamed into place"
  done
  ls -a "$work/out" | grep -q '\.png.\|^\.tr' && fail "temporary files left: $(ls -a "$work/out")"
  ;;
tube)
  # The tube pictures of the tight N = 2400 trefoil (bench/data, beside the 5th argument): four
  # PNGs of the asked size with real content, the grid data with the rows its header announces,
  # gnuplot silent (no warning in its log), no temporary left; --tube-size out of range or
  # without --plots refused; a later run without --plots removes the pictures and their files.
  command -v gnuplot >/dev/null || { echo "gnuplot not installed"; exit 77; }
  knot24=${5%/*}/trefoil_2400.vect
  "$tr" analyze "$knot24" --out "$work/out" -m 1 --plateau-eps 3e-3 --plots --tube-size 300 >"$work/stdout" 2>"$work/stderr" || fail "exit $?: $(cat "$work/stderr")"
  grep -q "^tube: $work/out/tube_{front,top,side,struts}.png" "$work/stdout" || fail "no tube line: $(cat "$work/stdout")"
  for f in tube_front tube_top tube_side tube_struts; do
    p=$work/out/$f.png
    [ "$(head -c 4 "$p" | od -An -c | tr -d ' ')" = '211PNG' ] || fail "$f.png is not a PNG"
    [ "$(stat -c %s "$p")" -gt 10000 ] || fail "$f.png is nearly empty: $(stat -c %s "$p") bytes"
    # IHDR: width and height, big-endian, at bytes 16 and 20
    [ "$(od -An -tu1 -j16 -N8 "$p" | tr -s ' ')" = ' 0 0 1 44 0 0 1 44' ] || fail "$f.png is not 300 x 300"
  done
  [ -s "$work/out/tube_gnuplot.log" ] && fail "gnuplot said: $(cat "$work/out/tube_gnuplot.log")"
  awk '/^# tube of radius 1: / { R = $6; K = $9 } /^[-0-9]/ { rows++ }
    END { exit !(R > 64 && K > 3 && rows == (R + 1) * (K + 1)) }' "$work/out/tube.dat" || fail "tube.dat rows: $(head -1 "$work/out/tube.dat")"
  ls -a "$work/out" | grep -q '\.tmp' && fail "temporary files left: $(ls -a "$work/out")"
  for bad in "--plots --tube-size 100" "--plots --tube-size 4001" "--tube-size 300"; do
    # shellcheck disable=SC2086
    "$tr" analyze "$knot24" --out "$work/bad" $bad >/dev/null 2>"$work/err"; rc=$?
    [ $rc = 2 ] || fail "$bad: exit $rc"
    grep -q '^tightrope analyze: --tube-size needs' "$work/err" || fail "$bad: $(cat "$work/err")"
    [ -e "$work/bad" ] && fail "$bad: left $work/bad behind"
  done
  "$tr" analyze "$knot24" --out "$work/out" -m 1 >/dev/null 2>&1 || fail "rerun without --plots"
  ls "$work/out" | grep -q 'tube\|struts' && fail "stale tube files: $(ls "$work/out")"
  ;;
cycles)
  # A trefoil tightened by our engine (N = 1600, bench/data) against the paper's published
  # structure: sigma-^9 has 18 fixed points forming two 9-cycles, one stable, and the stable
  # cycle passes within 0.5 of the paper's C9- = 0.189 15.674 ... 21.455, in the same order.
  "$tr" analyze "$5" --out "$work/out" -m 1 >"$work/stdout" 2>"$work/stderr" || fail "exit $?: $(cat "$work/stderr")"
  grep -q '"fixed_points": 18,' "$work/out/summary.json" || fail "not 18 fixed points"
  [ "$(grep -o '"period": 9, "stable": [01]' "$work/out/summary.json" | sort -u | wc -l)" = 2 ] || fail "not a stable and an unstable 9-cycle"
  got=$(grep -o '"period": 9, "stable": 1, "members": \[[^]]*\]' "$work/out/summary.json" | sed 's/.*\[//; s/\]//; s/,//g')
  want="0.189 15.674 32.370 11.103 26.588 10.541 22.018 4.759 21.455"
  awk -v g="$got" -v w="$want" 'BEGIN { n = split(g, a, " "); split(w, b, " "); if (n != 9) exit 1;
    for (i = 1; i <= 9; i++) { d = a[i] - b[i]; if (d < 0) d = -d; if (d > 0.5) exit 1 } }' || fail "stable cycle $got"
  ;;
usage)
  need_knot
  "$tr" analyze "$knot" >/dev/null 2>&1; [ $? = 2 ] || fail "no --out accepted"
  "$tr" analyze "$knot" --out "$work/o" -m 0 >/dev/null 2>&1; [ $? = 2 ] || fail "-m 0 accepted"
  "$tr" analyze "$knot" --out "$work/o" --jump-window 0.1 >/dev/null 2>&1; [ $? = 2 ] || fail "bad window accepted"
  "$tr" analyze "$work/no_such.vect" --out "$work/o" >/dev/null 2>"$work/err"; [ $? = 2 ] || fail "missing file"
  [ "$(wc -l <"$work/err")" = 1 ] || fail "more than one line: $(cat "$work/err")"
  "$tr" analyze --help | grep -q 'usage: tightrope analyze' || fail "help"
  ;;
options)
  need_knot
  # Each refused value: exit 2, one line that starts like every analyze message and names the
  # option, and no output directory left behind. Values accepted at the edges still run.
  refused() { want=$1; shift; rm -rf "$work/o"
    "$tr" analyze "$knot" --out "$work/o" "$@" >/dev/null 2>"$work/err"; rc=$?
    [ $rc = 2 ] || fail "$*: exit $rc: $(cat "$work/err")"
    [ "$(wc -l <"$work/err")" = 1 ] || fail "$*: not one line: $(cat "$work/err")"
    grep -q -e "^tightrope analyze: .*$want" "$work/err" || fail "$*: does not say '$want': $(cat "$work/err")"
    [ -e "$work/o" ] && fail "$*: left $work/o behind"; true; }
  refused --contact-bin --contact-bin 1e-300   # once SIGFPE: a bin count beyond size_t, then % 0
  refused --contact-bin --contact-bin 1e-6     # below L x 1e-7 of the scaled knot (L = 32.7)
  refused --contact-bin --contact-bin 5        # above L/8
  refused --contact-bin --contact-bin 0
  refused --contact-bin --contact-bin nan
  refused --power --power 0
  refused --power --power 101
  refused --power --power 2.5
  refused --power --power 1e300
  refused --plateau-min --plateau-min 0
  refused --plateau-min --plateau-min 1.5
  refused --plateau-min --plateau-min 1e300
  refused --plateau-min --plateau-min 401      # more than the 400 vertices
  refused --plateau-eps --plateau-eps 1
  refused --strut-tol --strut-tol -1
  refused -m -m 0
  refused -m -m 1e300
  refused -m -m 101                            # N = 400: fewer than 4 averaged vertices
  refused --jump-at --jump-at 1,inf
  refused --jump-window --jump-window 0.1,inf
  refused "unknown option '--bogus'" --bogus   # last on the line: not 'needs a value'
  refused "unknown option '--bogus'" --bogus -m 2
  refused "--power needs a value" --power
  for ok in "--contact-bin 0.004 --power 100 --plateau-min 400" "--contact-bin 4 --power 1 -m 100"; do
    rm -rf "$work/o"
    # shellcheck disable=SC2086
    "$tr" analyze "$knot" --out "$work/o" $ok >/dev/null 2>"$work/err" || fail "$ok refused: $(cat "$work/err")"
    [ -s "$work/o/summary.json" ] || fail "$ok: no summary"
  done
  ;;
nodir)
  need_knot
  # A bad input is found before anything is made: no empty output directory.
  printf 'VECT\n1 3 0\n3\n0\n0 0 0\n1 0 0\n' >"$work/short.vect"
  # (open ropes are analysed since issue 23; one of 3 vertices is too short for a profile)
  printf 'VECT\n1 3 0\n3\n0\n0 0 0\n1 0 0\n1 1 0\n' >"$work/open.vect"
  for f in "$work/no_such.vect" "$work/short.vect" "$work/open.vect"; do
    "$tr" analyze "$f" --out "$work/o" >/dev/null 2>"$work/err"; rc=$?
    [ $rc = 2 ] || fail "$f: exit $rc: $(cat "$work/err")"
    grep -q '^tightrope analyze: ' "$work/err" || fail "$f: message $(cat "$work/err")"
    [ -e "$work/o" ] && fail "$f: left $work/o behind"
  done
  # an existing file where the directory should go: refused, the file untouched
  echo keep >"$work/file"
  "$tr" analyze "$knot" --out "$work/file" >/dev/null 2>"$work/err"; rc=$?
  [ $rc = 2 ] || fail "--out FILE: exit $rc (an output the user can fix)"
  grep -q "^tightrope analyze: cannot create directory $work/file" "$work/err" || fail "--out FILE: $(cat "$work/err")"
  [ "$(cat "$work/file")" = keep ] || fail "--out FILE overwritten"
  ;;
*) fail "unknown case $case_" ;;
esac
echo PASS
