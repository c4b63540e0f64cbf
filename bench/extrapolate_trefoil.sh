#!/usr/bin/env bash
# The ideal trefoil's ropelength by extrapolation (issue 23 item 3):
#   bench/extrapolate_trefoil.sh OUTDIR [N ...]        (default N: 2400 4800 9600 19200)
# For each N, one after the other:
#   1. tightrope tighten START --n N -o OUTDIR/tN.vect   (the second-order solver on the
#      spline-resampled tight N = 2400 trefoil; a start that the resampling leaves
#      overlapping, N < 2400, is retried with --scale)
#   2. up to RESOLVES times (default 2): bench/newton_run on the current curve, from
#      scratch (fresh penalty and multipliers). A shorter result replaces the curve; the
#      change the last re-solve made, or would have made (its last iterate's length, when
#      it was not shorter but ended feasible to 1e-9; then the re-solves stop, the next
#      would be the same), is the point's convergence uncertainty s, at least 1e-9 (a
#      re-solve that does not get back to feasibility leaves the floor). Bars too small
#      for the points' scatter show in the fit's chi^2, which scales the error up.
#   3. L = `tightrope measure` of the final curve; with N <= KKT_MAX_N (default 2400,
#      the certificate costs minutes above), its KKT residual.
# A row "N L s kkt tighten_s resolve_changes stop" goes to OUTDIR/ladder.tsv (a done N is
# kept: rerunning resumes), then build/ropelength_extrap fits L(N) = L_inf + c/N^2 (+ more
# powers if chi2 asks) and compares with the paper's 32.7429345 (OUTDIR/fit.txt).
# Environment: BUILD (default build), START (default bench/data/trefoil_2400.vect),
# RESOLVES, RESOLVE_TIME (seconds per re-solve, default 600), TIME_LIMIT (tighten's,
# default 900), KKT_MAX_N, PREV (another run's ladder.tsv: s is at least the change from
# its value at the same N). Heavy: run it niced, alone (the times:
# bench/notes/2026-11-25-extrapolation.md).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:?usage: extrapolate_trefoil.sh OUTDIR [N ...]}
shift
ns=("$@")
[ ${#ns[@]} -gt 0 ] || ns=(2400 4800 9600 19200)
build=${BUILD:-$here/build}
start=${START:-$here/bench/data/trefoil_2400.vect}
resolves=${RESOLVES:-2}
resolve_time=${RESOLVE_TIME:-600}
time_limit=${TIME_LIMIT:-900}
kkt_max=${KKT_MAX_N:-2400}
tr=$build/tightrope
nr=$build/newton_run
fit=$build/ropelength_extrap
for x in "$tr" "$nr" "$fit"; do
    [ -x "$x" ] || { echo "extrapolate_trefoil: $x not built (cmake --build build)" >&2; exit 2; }
done
mkdir -p "$out"
table=$out/ladder.tsv
[ -f "$table" ] || printf '# N\tL\ts\tkkt\ttighten_s\tresolve_changes\tstop\n' >"$table"

ropelength() { "$tr" measure "$1" --json | sed -n 's/.*"ropelength": \([-0-9.e+]*\).*/\1/p' | head -1; }

for n in "${ns[@]}"; do
    if awk -v n="$n" '$1 == n { f = 1 } END { exit !f }' "$table"; then
        echo "N = $n: done (in $table)" >&2
        continue
    fi
    cur=$out/t$n.vect
    t0=$(date +%s.%N)
    if ! "$tr" tighten "$start" --n "$n" --time-limit "$time_limit" -o "$cur" --json >"$out/t$n.json" 2>"$out/t$n.err"; then
        if grep -q 'overlaps itself' "$out/t$n.err"; then
            "$tr" tighten "$start" --n "$n" --scale --time-limit "$time_limit" -o "$cur" --json >"$out/t$n.json" 2>"$out/t$n.err"
        else
            cat "$out/t$n.err" >&2
            exit 1
        fi
    fi
    t1=$(date +%s.%N)
    stop=$(sed -n 's/.*"stop": "\([^"]*\)".*/\1/p' "$out/t$n.json")
    l=$(ropelength "$cur")
    echo "N = $n: tighten $stop, $l in $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s" >&2
    changes=""
    s=1e-9
    for ((k = 1; k <= resolves; k++)); do
        next=$out/t$n.r$k.vect
        "$nr" "$cur" "$next" 0 "$resolve_time" >"$out/t$n.r$k.log" 2>&1 || true
        # the last iterate's length, if it is feasible (violation <= 1e-9): a re-solve that
        # did not get back to feasibility within its time says nothing about the point
        settled=$(awk '$1 == "it" { v = $6; f = ($8 + 0 <= 1e-9) } END { if (f) print v }' "$out/t$n.r$k.log")
        if [ -f "$next" ]; then
            lk=$(ropelength "$next")
            cur=$next
        else
            lk=$l
        fi
        # the move this re-solve made (accepted) or would have made (its settled length)
        d=$(awk -v a="$l" -v b="$lk" -v c="${settled:-$l}" 'BEGIN { d = b - a; if (b == a) d = c - a; printf "%.3e", d }')
        s=$(awk -v d="$d" 'BEGIN { d = d < 0 ? -d : d; if (d < 1e-9) d = 1e-9; printf "%.3e", d }')
        changes="$changes${changes:+,}$d"
        echo "N = $n: re-solve $k: $lk (change $d)" >&2
        l=$lk
        [ -f "$next" ] || break # not shorter: a further re-solve from the same curve is the same
    done
    # another run's value at this N (PREV: its ladder.tsv, e.g. an earlier solver's): the
    # change between two solvers that both stopped converged is part of the point's bar
    if [ -n "${PREV:-}" ]; then
        s=$(awk -v n="$n" -v l="$l" -v s="$s" '$1 == n { d = $2 - l; d = d < 0 ? -d : d; if (d > s) s = d }
            END { printf "%.3e", s }' "$PREV")
    fi
    kkt=-
    if [ "$n" -le "$kkt_max" ]; then
        kkt=$("$tr" measure "$cur" --json --kkt | sed -n 's/.*"kkt": {"residual": \([-0-9.e+]*\).*/\1/p')
    fi
    cp "$cur" "$out/final_$n.vect"
    printf '%s\t%s\t%s\t%s\t%.1f\t%s\t%s\n' "$n" "$l" "$s" "$kkt" \
        "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" "${changes:--}" "$stop" >>"$table"
done
sort -n -k1,1 "$table" | grep -v '^#' | "$fit" - --ref 32.7429345 | tee "$out/fit.txt"
