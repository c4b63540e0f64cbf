#!/usr/bin/env bash
# Every relative link of the documentation resolves: README.md, docs/*.md,
# bench/*.md and bench/notes/*.md. A link [text](path) or ![alt](path) must name
# an existing file or folder, relative to the page that holds it; a #fragment on
# a Markdown page must be one of its headings, slugged as GitHub does (lower
# case, punctuation dropped, spaces to hyphens). Links with a scheme
# (http:, mailto:, ...) are not checked. One line per broken link, exit 1 if any.
# Usage: doc_links.sh SOURCE_DIR
set -u
root=${1:?usage: doc_links.sh SOURCE_DIR}
cd "$root" || exit 2

# The GitHub anchors of a Markdown file's headings, one a line (fenced code
# skipped; the -1, -2 suffixes of repeated headings are not produced).
anchors() {
    awk '/^```/ { fence = !fence; next }
         !fence && /^#+ / {
             h = $0; sub(/^#+ +/, "", h); h = tolower(h)
             gsub(/[^a-z0-9 _-]/, "", h); gsub(/ /, "-", h); print h
         }' "$1"
}

bad=0
checked=0
shopt -s nullglob
for page in README.md docs/*.md bench/*.md bench/notes/*.md; do
    [[ -f $page ]] || continue
    dir=$(dirname "$page")
    # links outside fenced code blocks, one target a line: "LINE<TAB>TARGET"
    while IFS=$'\t' read -r line target; do
        case $target in
            *://* | mailto:*) continue ;;
        esac
        checked=$((checked + 1))
        path=${target%%#*}
        frag=
        [[ $target == *'#'* ]] && frag=${target#*#}
        if [[ -z $path ]]; then
            file=$page
        else
            file=$dir/$path
        fi
        if [[ ! -e $file ]]; then
            echo "$page:$line: broken link: $target (no $file)"
            bad=$((bad + 1))
            continue
        fi
        if [[ -n $frag && $file == *.md ]] && ! anchors "$file" | grep -qxF -- "$frag"; then
            echo "$page:$line: broken link: $target (no heading #$frag in $file)"
            bad=$((bad + 1))
        fi
    done < <(awk '/^```/ { fence = !fence; next }
                  !fence {
                      s = $0
                      while (match(s, /\]\([^) ]+\)/)) {
                          print FNR "\t" substr(s, RSTART + 2, RLENGTH - 3)
                          s = substr(s, RSTART + RLENGTH)
                      }
                  }' "$page")
done

if ((checked == 0)); then
    echo "doc_links: no links found under $root (wrong folder?)"
    exit 1
fi
if ((bad > 0)); then
    echo "doc_links: $bad broken of $checked relative links"
    exit 1
fi
echo "doc_links: all $checked relative links resolve"
