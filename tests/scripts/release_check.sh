#!/usr/bin/env bash
# The knot table's data release in the repository (issue 47 item 4; release/*/, made by
# scripts/gallery.py): checked independently of the runs that made it. For every knot of its
# table.tsv: the committed curve (curves/NAME.vect.xz) measured by the oracle has the table's
# ropelength (to 1e-9), is thick (thickness 1 to 1e-9, as every row says), is the named knot
# (`measure --identify NAME`: its invariants are the table's knot's), and its difference to the
# reference is the table's reference subtracted; the page, opened in a real headless browser,
# has the knot's row and its picture drawn. The release's README states how many knots are at or
# below the reference: the table must say the same.
# Usage: release_check.sh TIGHTROPE RELEASE_DIR WORK_DIR. Exit 0 pass, 1 fail.
set -u
tr=$1 rel=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
[ -f "$rel/table.tsv" ] || fail "$rel/table.tsv missing"
browser=$(command -v chromium-headless-shell || command -v chromium || true)
[ -n "$browser" ] || fail "no headless browser (scripts/deps.sh installs chromium-headless-shell)"
dom=$("$browser" --no-sandbox --disable-gpu --disable-dev-shm-usage --user-data-dir="$work/profile" \
  --virtual-time-budget=10000 --dump-dom "file://$(cd "$rel" && pwd)/index.html" 2>/dev/null)
grep -q 'data-checked="1"' <<<"$dom" || fail "the page's load check did not run in $browser"
# the columns by the header's names
header=$(head -1 "$rel/table.tsv")
col() { tr '\t' '\n' <<<"$header" | grep -nx "$1" | cut -d: -f1; }
c_knot=$(col knot) c_rl=$(col ropelength) c_th=$(col thickness) c_ref=$(col ref_ropelength) c_diff=$(col diff)
[ -n "$c_knot" ] && [ -n "$c_rl" ] && [ -n "$c_th" ] && [ -n "$c_ref" ] && [ -n "$c_diff" ] ||
  fail "table.tsv lacks a column (knot, ropelength, thickness, ref_ropelength, diff)"
n=0 below=0
while IFS=$'\t' read -r -a f; do
  k=${f[c_knot - 1]} rl=${f[c_rl - 1]} th=${f[c_th - 1]} ref=${f[c_ref - 1]} diff=${f[c_diff - 1]}
  n=$((n + 1))
  xz -dc "$rel/curves/$k.vect.xz" >"$work/$k.vect" 2>/dev/null || fail "$k: curves/$k.vect.xz unreadable"
  m=$("$tr" measure "$work/$k.vect" | tail -1) || fail "$k: measure failed"
  read -r _ _ _ _ _ mth mrl _ <<<"$m"
  awk -v a="$mrl" -v b="$rl" 'BEGIN { exit !((a - b) ^ 2 <= (1e-9 * b) ^ 2) }' ||
    fail "$k: the curve measures $mrl, the table says $rl"
  awk -v a="$mth" -v b="$th" 'BEGIN { exit !(a >= 1 - 1e-9 && (a - b) ^ 2 <= 1e-18) }' ||
    fail "$k: thickness $mth (the table: $th)"
  "$tr" measure --identify "$k" "$work/$k.vect" >"$work/$k.id" 2>&1 || fail "$k: not $k: $(cat "$work/$k.id")"
  awk -v r="$rl" -v q="$ref" -v d="$diff" 'BEGIN { exit !((r - q - d) ^ 2 <= 1e-18) }' ||
    fail "$k: diff $diff is not $rl - $ref"
  awk -v d="$diff" 'BEGIN { exit !(d <= 0) }' && below=$((below + 1))
  grep -q "<tr id=\"knot-$k\">" <<<"$dom" || fail "no row for $k on the page"
  grep -Eq "<img src=\"pictures/$k.png\"[^>]*data-shown=\"1\"" <<<"$dom" || fail "$k's picture not drawn"
done < <(tail -n +2 "$rel/table.tsv")
[ "$n" -gt 0 ] || fail "an empty table"
grep -q "\*\*$below of $n\*\* at or below" "$rel/README.md" ||
  fail "README.md does not say **$below of $n** at or below (the table's count)"
echo "release $rel: $n knots, each measured, identified and on the page; $below of $n at or below the reference"
exit 0
