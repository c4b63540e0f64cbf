#!/usr/bin/env bash
# One plain command per knot (issue 47 item 3): `make knot NAME`, then `tighten START -o OUT
# --time-limit T` with no other flag, the result measured by `tightrope measure` and compared
# with KnotInfo's ropelength (data/knots/knotinfo_knots.tsv). Resumable: a knot with a row in
# OUTDIR/table.tsv is skipped.
#   bench/plain_knots.sh OUTDIR T NAME...          e.g. bench/plain_knots.sh out 300 9_1 9_2
#   bench/plain_knots.sh OUTDIR T --crossings C    every prime knot of C crossings
# Environment: BUILD (default build/) holds tightrope. Rows: name, N, ropelength, KnotInfo,
# difference (%), seconds of wall clock, the run's exit status, the load average at its start.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:?OUTDIR}
t=${2:?T}
shift 2
tr=${BUILD:-$here/build}/tightrope
table=$here/data/knots/knotinfo_knots.tsv
[ -x "$tr" ] || { echo "plain_knots: $tr not built" >&2; exit 2; }
if [ "${1:-}" = --crossings ]; then
    mapfile -t names < <(awk -F'\t' -v c="$2" '!/^#/ && $2 == c { print $1 }' "$table")
else
    names=("$@")
fi
mkdir -p "$out"
[ -f "$out/table.tsv" ] || printf 'name\tN\tropelength\tknotinfo\tdiff_pct\tseconds\texit\tload\n' >"$out/table.tsv"
for k in "${names[@]}"; do
    awk -F'\t' -v k="$k" '$1 == k { f = 1 } END { exit !f }' "$out/table.tsv" && continue
    ki=$(awk -F'\t' -v k="$k" '!/^#/ && $1 == k { print $8 }' "$table")
    "$tr" make knot "$k" -o "$out/$k.start.vect" >/dev/null
    load=$(cut -d' ' -f1 /proc/loadavg)
    t0=$(date +%s.%N)
    rc=0
    "$tr" tighten "$out/$k.start.vect" -o "$out/$k.vect" --time-limit "$t" \
        >"$out/$k.out" 2>"$out/$k.err" || rc=$?
    secs=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
    read -r n rl < <("$tr" measure "$out/$k.vect" 2>/dev/null | awk '$1 == "curve" { print $2, $7 }' || echo "- -")
    d=$(awk -v r="${rl:--}" -v w="$ki" 'BEGIN { if (r == "-" || w == "") print "-"; else printf "%+.4f", (r - w) / w * 100 }')
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$k" "${n:--}" "${rl:--}" "$ki" "$d" "$secs" "$rc" "$load" >>"$out/table.tsv"
done
awk -F'\t' 'NR > 1 && $5 != "-" { n++; if ($5 + 0 <= 0) b++ } END { printf "%d of %d at or below KnotInfo\n", b, n }' "$out/table.tsv"
