#!/usr/bin/env bash
# Writes a tightrope batch manifest (stdout) of the prime knots or links of the tables the
# repository holds, by name -- no start files, nothing outside the checkout:
#   bench/names_manifest.sh knots [MIN] MAX [TIGHTEN-OPTIONS...] > knots.tsv
#   bench/names_manifest.sh links [MIN] MAX [TIGHTEN-OPTIONS...] > links.tsv
#   tightrope batch knots.tsv -o table --compare knotinfo
#   tightrope batch links.tsv -o links --compare bench/data/link_ropelength.tsv
# knots: KnotInfo's prime knots of MIN..MAX crossings (data/knots/knotinfo_knots.tsv; MIN
# defaults to 3, MAX at most 12), each line `NAME<TAB>knot NAME<TAB>-<TAB>OPTIONS`, in KnotInfo's
# order (3_1, 4_1, 5_1, 5_2, ... 10_165, 11a_1 ...).
# links: LinkInfo's prime links of MIN..MAX crossings (data/knots/linkinfo_links.tsv; MIN
# defaults to 2, MAX at most 9), one line per link (its first orientation: the ropelength does
# not depend on it), named by its Rolfsen name in KnotPlot's dotted form (6^3_2, the Borromean
# rings, is 6.3.2, as in bench/data/link_ropelength.tsv), its start `link L6a4`.
# N is '-' (tighten chooses); TIGHTEN-OPTIONS default to '--time-limit 300' (the plain
# command of issue 47); a single '-' gives none. The bench/knot_table_manifest.sh and
# bench/link_table_manifest.sh of the KnotPlot starts in ../shared remain for the notes' runs.
set -euo pipefail
usage() { echo "usage: names_manifest.sh knots|links [MIN] MAX [TIGHTEN-OPTIONS...]" >&2; exit 2; }
[ $# -ge 2 ] || usage
kind=$1
shift
is_int() { [[ $1 =~ ^[0-9]+$ ]]; }
is_int "$1" || usage
if [ $# -ge 2 ] && is_int "$2"; then min=$1 max=$2; shift 2; else max=$1; min=; shift; fi
data=$(cd "$(dirname "$0")/../data/knots" && pwd)
case $kind in
knots) table=$data/knotinfo_knots.tsv top=12 min=${min:-3} ;;
links) table=$data/linkinfo_links.tsv top=9 min=${min:-2} ;;
*) usage ;;
esac
[ "$max" -le "$top" ] || { echo "names_manifest.sh: the $kind table reaches $top crossings, not $max" >&2; exit 2; }
[ "$min" -le "$max" ] || { echo "names_manifest.sh: MIN $min is above MAX $max" >&2; exit 2; }
[ -f "$table" ] || { echo "names_manifest.sh: no $table" >&2; exit 2; }
if [ $# -eq 0 ]; then opts="--time-limit 300"; elif [ "$*" = - ]; then opts=; else opts=$*; fi
printf 'name\tstart\tN\toptions\n'
# the tables: '#' comments, then a header naming the columns
awk -F'\t' -v kind="$kind" -v min="$min" -v max="$max" -v opts="$opts" '
  /^#/ { next }
  !head { for (i = 1; i <= NF; i++) col[$i] = i; head = 1; next }
  { c = $col["crossings"] + 0; if (c < min || c > max) next }
  kind == "knots" { printf "%s\tknot %s\t-\t%s\n", $1, $1, opts; next }
  seen[$col["unoriented"]]++ { next }
  { r = $col["rolfsen"]; gsub(/[\^_]/, ".", r)
    printf "%s\tlink %s\t-\t%s\n", r, $col["unoriented"], opts }' "$table"
