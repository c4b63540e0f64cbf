#!/usr/bin/env bash
# Writes a tightrope batch manifest (stdout) of the prime knots of the TightKnot peer table up
# to MAX crossings, each from its KnotPlot loose start at the table's N:
#   bench/knot_table_manifest.sh [MAX [TIGHTEN-OPTIONS...]] > knots.tsv
#   tightrope batch knots.tsv -o table --compare ../shared/data/tightknot_ropelength.tsv
# MAX defaults to 8 (3_1 ... 8_21, 35 knots); the options to '--scale --time-limit 120', the
# route of the issue 24 figures. Paths are absolute, so the manifest can be written anywhere.
# SHARED (default: ../shared beside the checkout) holds data/.
set -euo pipefail
max=${1:-8}
shift || true
opts=${*:---scale --time-limit 120}
shared=$(cd "${SHARED:-$(dirname "$0")/../../shared}" && pwd)
table=$shared/data/tightknot_ropelength.tsv
[ -f "$table" ] || { echo "knot_table_manifest.sh: no $table (SHARED=...)" >&2; exit 2; }
printf 'name\tfile\tN\toptions\n'
awk -F'\t' -v max="$max" -v kp="$shared/data/knotplot" -v opts="$opts" '
  NR > 1 { split($1, c, "_"); if (c[1] + 0 <= max) printf "%s\t%s/%s.%s.vect\t%s\t%s\n", $1, kp, c[1], c[2], $2, opts }' "$table"
