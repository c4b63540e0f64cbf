#!/usr/bin/env bash
# Writes a tightrope batch manifest (stdout) of the links of the KnotPlot set up to MAX crossings
# (C.c.k.vect, c >= 2 components; the unlinks 0.c.1 with them), each at N vertices per component
# of max(128, 56 C / c) -- about the knots' table's vertices per crossing:
#   bench/link_table_manifest.sh [MAX [TIGHTEN-OPTIONS...]] > links.tsv
#   tightrope batch links.tsv -o links --compare bench/data/link_ropelength.tsv
# MAX defaults to 7 (21 links); the options to '--scale --time-limit 120'.
# SHARED (default: ../shared beside the checkout) holds data/.
set -euo pipefail
max=${1:-7}
shift || true
opts=${*:---scale --time-limit 120}
shared=$(cd "${SHARED:-$(dirname "$0")/../../shared}" && pwd)
kp=$shared/data/knotplot
[ -d "$kp" ] || { echo "link_table_manifest.sh: no $kp (SHARED=...)" >&2; exit 2; }
printf 'name\tfile\tN\toptions\n'
for f in "$kp"/*.*.*.vect; do
  b=$(basename "$f" .vect)
  IFS=. read -r cr comp idx <<< "$b"
  [ "$cr" -le "$max" ] || continue
  n=$(( 56 * cr / comp ))
  [ "$n" -ge 128 ] || n=128
  printf '%s\t%s\t%s\t%s\n' "$b" "$f" "$n" "$opts"
done | sort -t. -k1,1n -k2,2n -k3,3n
