#!/usr/bin/env bash
# scripts/gallery.py (issue 47 item 4): a batch's results as a release folder, the page opened in
# a real headless browser (chromium-headless-shell, scripts/deps.sh). Checked: every knot of the
# table has its row, its picture drawn by the browser (the page marks each <img> the browser
# decoded; a picture removed is caught), its curve (xz, the batch's bytes) and the table copied;
# refusals: a release folder that exists (left as it was), one inside the batch folder, a table
# that is not a batch's (file:line); an interrupted run (SIGINT, SIGTERM) or a failing one
# leaves no release and no temporary folder.
# Usage: gallery_cli.sh TIGHTROPE SOURCE_DIR WORK_DIR. Exit 0 pass, 1 fail.
set -u
tr=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
browser=$(command -v chromium-headless-shell || command -v chromium || true)
[ -n "$browser" ] || fail "no headless browser (scripts/deps.sh installs chromium-headless-shell)"
gallery=(python3 "$src/scripts/gallery.py")
# a batch of two knots (the TightKnot curves in tests/data), briefly tightened
mkdir "$work/starts"
cp "$src/tests/data/tightknot/3_1.vect" "$src/tests/data/tightknot/4_1.vect" "$work/starts/"
"$tr" batch "$work/starts" -o "$work/batch" --compare knotinfo -- --scale --steps 20 --no-kkt >/dev/null 2>&1 ||
  fail "batch"
before=$(cd "$work/batch" && find . -type f -exec sha256sum {} + | sort)
"${gallery[@]}" "$work/batch" -o "$work/rel" --tightrope "$tr" --title "two knots" >"$work/g.out" 2>"$work/g.err" ||
  fail "gallery: $(cat "$work/g.err")"
after=$(cd "$work/batch" && find . -type f -exec sha256sum {} + | sort)
[ "$before" = "$after" ] || fail "the gallery wrote into the batch folder"
cmp -s "$work/batch/table.tsv" "$work/rel/table.tsv" || fail "table.tsv not the batch's"
cmp -s "$work/batch/table.json" "$work/rel/table.json" || fail "table.json not the batch's"
for k in 3_1 4_1; do
  xz -dc "$work/rel/curves/$k.vect.xz" | cmp -s - "$work/batch/$k.vect" || fail "curves/$k.vect.xz is not the batch's curve"
done
# the page in the browser: its DOM after load
view() {
  # no sandbox (CI runs as root), /tmp instead of a container's small /dev/shm, its profile
  # in the work folder, not in HOME
  "$browser" --no-sandbox --disable-gpu --disable-dev-shm-usage --user-data-dir="$work/profile" \
    --virtual-time-budget=10000 --dump-dom "file://$1/index.html" 2>/dev/null
}
dom=$(view "$work/rel")
grep -q 'data-checked="1"' <<<"$dom" || fail "the page's load check did not run in $browser"
for k in 3_1 4_1; do
  grep -q "<tr id=\"knot-$k\">" <<<"$dom" || fail "no row for $k"
  grep -Eq "<img src=\"pictures/$k.png\"[^>]*data-shown=\"1\"" <<<"$dom" || fail "$k's picture not drawn"
done
# the check can fail: a release with a picture missing shows it undrawn
cp -r "$work/rel" "$work/rel-broken" && rm "$work/rel-broken/pictures/4_1.png"
grep -Eq '<img src="pictures/4_1.png"[^>]*data-shown="0"' <<<"$(view "$work/rel-broken")" ||
  fail "a missing picture was not caught"
# refusals
echo keep >"$work/exists"
"${gallery[@]}" "$work/batch" -o "$work/exists" --tightrope "$tr" 2>"$work/e1" && fail "an existing release accepted"
[ "$(cat "$work/exists")" = keep ] || fail "an existing file was replaced"
grep -q "exists" "$work/e1" || fail "no message: $(cat "$work/e1")"
"${gallery[@]}" "$work/batch" -o "$work/batch/rel" --tightrope "$tr" 2>"$work/e2" && fail "a release inside the batch accepted"
[ -e "$work/batch/rel" ] && fail "wrote into the batch folder"
mkdir "$work/bad" && printf 'knot\tN\nx\t1\n' >"$work/bad/table.tsv"
"${gallery[@]}" "$work/bad" -o "$work/rel2" --tightrope "$tr" 2>"$work/e3" && fail "a table without ropelengths accepted"
grep -q "table.tsv:2: no 'ropelength'" "$work/e3" || fail "no file:line message: $(cat "$work/e3")"
# interrupted (SIGINT, SIGTERM) while it draws: no release, no temporary folder
for sig in INT TERM; do
  timeout -s $sig 1 "${gallery[@]}" "$work/batch" -o "$work/rel-$sig" --tightrope "$tr" 2>"$work/i-$sig.err" &&
    fail "SIG$sig: the gallery finished within 1 s: nothing tested"
  grep -q "interrupted; no release written" "$work/i-$sig.err" || fail "SIG$sig: $(cat "$work/i-$sig.err")"
  [ -e "$work/rel-$sig" ] && fail "SIG$sig left a release"
  ls -a "$work" | grep -q "^\.rel-$sig\." && fail "SIG$sig left a temporary folder"
done
# a failing picture (no such program) leaves no release, and no temporary folder
"${gallery[@]}" "$work/batch" -o "$work/rel3" --tightrope /nonexistent/tightrope 2>"$work/e4" && fail "no program, yet done"
ls -a "$work" | grep -q '^\.rel3\.' && fail "a temporary folder was left"
[ -e "$work/rel3" ] && fail "a half-made release was left"
[ "$(wc -l <"$work/e4")" = 1 ] && grep -q "^gallery: /nonexistent/tightrope: cannot run" "$work/e4" ||
  fail "not a one-line error: $(cat "$work/e4")"
exit 0
