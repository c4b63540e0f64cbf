#!/usr/bin/env bash
# The second-order solver's ladder, each rung spline-refined from the converged one before it,
# with every checkpoint measured as it is written (the ropelength-against-time curve):
#   bench/trefoil_ladder.sh OUTDIR [N ...]     (default N: 4800 9600 19200 38400 102400)
# Start: START (default bench/data/trefoil_2400.vect). Each rung: `newton_run PREV OUTDIR/LN.vect
# sN TIME_LIMIT CKPT` (TIME_LIMIT default 6000 s; CKPT 300 s at N >= 10^5, else 600 s), its
# progress in OUTDIR/LN.log, its `/usr/bin/time -v` in OUTDIR/LN.err. OUTDIR/curve.txt gets a
# line "N seconds-since-start <tightrope measure's line>" per checkpoint and per rung result;
# OUTDIR/curve.png plots it when gnuplot is there. Heavy
# (bench/notes/2026-11-28-n102400-settles.md: 51 minutes to 102 400 on the 2-core VM):
# run it alone, in the background.
# Resumable: a rung whose OUTDIR/LN.vect exists is skipped. Every rung keeps the solver's state
# (newton_run --state: OUTDIR/LN.vect.state, the iterate as the solver holds it with its
# multipliers, penalty and loop counters, every CKPT seconds and when it is stopped); a rung with
# a state goes on from it (newton_run --resume: the steps the stopped run had left), the state
# moved aside first to OUTDIR/resumeN.state (an input is never written over). Without a state, a
# rung with a checkpoint (OUTDIR/LN.vect.ckpt, the best iterate rescaled to thickness 1: most of
# the progress lost, see bench/newton_run.c) restarts from it, not from the rung below.
# The seconds in curve.txt count from this invocation's start (a resumed ladder's are its own).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:?usage: trefoil_ladder.sh OUTDIR [N ...]}
shift
ns=("$@")
[ ${#ns[@]} -gt 0 ] || ns=(4800 9600 19200 38400 102400)
build=${BUILD:-$here/build}
prev=${START:-$here/bench/data/trefoil_2400.vect}
limit=${TIME_LIMIT:-6000}
tr=$build/tightrope
nr=$build/newton_run
for x in "$tr" "$nr"; do
    [ -x "$x" ] || { echo "trefoil_ladder: $x not built (cmake --build build)" >&2; exit 2; }
done
timer=()
[ -x /usr/bin/time ] && timer=(/usr/bin/time -v)
mkdir -p "$out"
t0=$(date +%s)
measure() { echo "$1 $(($(date +%s) - t0)) $("$tr" measure "$2" | tail -1)" >>"$out/curve.txt"; }
for n in "${ns[@]}"; do
    if [ -f "$out/L$n.vect" ]; then
        prev=$out/L$n.vect
        continue
    fi
    ck=600
    [ "$n" -ge 100000 ] && ck=300
    from=$prev
    size=s$n
    resume=()
    if [ -f "$out/L$n.vect.state" ]; then
        # the stopped run's state, of the curve this rung starts from (its shape is all that is
        # taken from it): moved aside, as the resumed run writes LN.vect.state anew
        mv -f "$out/L$n.vect.state" "$out/resume$n.state"
        resume=(--resume "$out/resume$n.state")
        echo "resuming N = $n from its state" >>"$out/L$n.log"
    elif [ -f "$out/resume$n.state" ]; then
        # a resumed run stopped before it wrote a state of its own
        resume=(--resume "$out/resume$n.state")
        echo "resuming N = $n from its state (again)" >>"$out/L$n.log"
    elif [ -f "$out/L$n.vect.ckpt" ]; then
        # the stopped run's best iterate, already N vertices: no resampling
        cp "$out/L$n.vect.ckpt" "$out/resume$n.vect"
        from=$out/resume$n.vect
        size=0
        echo "resuming N = $n from its checkpoint" >>"$out/L$n.log"
    fi
    "${timer[@]}" "$nr" --state ${resume[@]+"${resume[@]}"} "$from" "$out/L$n.vect" "$size" "$limit" "$ck" \
        >>"$out/L$n.log" 2>>"$out/L$n.err" &
    pid=$!
    last=""
    while kill -0 "$pid" 2>/dev/null; do
        sleep 10
        if [ -f "$out/L$n.vect.ckpt" ]; then
            m=$(stat -c %Y "$out/L$n.vect.ckpt")
            if [ "$m" != "$last" ]; then
                last=$m
                cp "$out/L$n.vect.ckpt" "$out/ck$n.vect"
                measure "$n" "$out/ck$n.vect"
            fi
        fi
    done
    wait "$pid" || { echo "trefoil_ladder: N = $n failed: $(tail -1 "$out/L$n.err")" >&2; exit 1; }
    [ -f "$out/L$n.vect" ] || { echo "trefoil_ladder: N = $n wrote no result (see $out/L$n.log)" >&2; exit 1; }
    measure "$n" "$out/L$n.vect"
    # the rung is done: its states are spent
    rm -f "$out/L$n.vect.state" "$out/resume$n.state"
    prev=$out/L$n.vect
done
if command -v gnuplot >/dev/null; then
    gnuplot <<GP
set terminal pngcairo size 900,560 noenhanced
set output "$out/curve.png"
set title "Trefoil ladder to N = ${ns[-1]}"
set xlabel "wall time since the start of the ladder (minutes)"
set ylabel "ropelength - 32.742934 (tightrope measure)"
set logscale y
set format y "%.0e"
set grid
plot "$out/curve.txt" using (\$2/60):(\$9-32.742934) with linespoints pt 7 title "checkpoints and rung results", \
     "$out/curve.txt" using (\$2/60):(\$9-32.742934):(sprintf("%d", \$1)) with labels offset 0,1 notitle, \
     1e-6 with lines dt 2 title "32.742935"
GP
fi
cat "$out/curve.txt"
