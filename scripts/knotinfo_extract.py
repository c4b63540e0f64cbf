#!/usr/bin/env python3
"""Extracts the knot and link tables Tightrope makes starts from (issue 47).

Run by hand, not by the build; its output is committed:

    python3 scripts/knotinfo_extract.py CSV_DIR [--version V] [--max-knot 12] [--max-link 9]

CSV_DIR holds knotinfo_data_complete.csv and linkinfo_data_complete.csv from
the `database_knotinfo` wheel (pip download database_knotinfo; unzip it;
database_knotinfo/csv_data/). Those files separate fields with '|' and carry
a second header line of descriptions, which is skipped.

Writes data/knots/knotinfo_knots.tsv and data/knots/linkinfo_links.tsv, tab
separated, with '#' comment lines naming the source (KnotInfo/LinkInfo via
database_knotinfo, GPL-3.0; Tightrope is GPL-3.0-or-later). They are facts
about knots, which the build embeds into the binary (cmake/EmbedText.cmake).

Knots: name, crossings, braid word (KnotInfo's, generators 1..s-1, a minus
sign for the inverse; where KnotInfo lists two, the first), PD code (KnotInfo's), Alexander polynomial in Conway's
normalisation (coefficients of t^-h .. t^h, Delta(1) = 1; KnotInfo lists a
positive leading coefficient, which is changed to Delta(1) = 1 here),
determinant, signature, KnotInfo's ropelength (empty where it has none).
The script checks that the determinant is |Delta(-1)|, Delta(1) = +-1, and
that every braid's closure has the right number of components.

Links: name (oriented, L2a1{0}), unoriented name, Rolfsen name, components,
crossings, strands, braid word, PD code, determinant, linking numbers (the
upper triangle of the linking matrix, row by row).
"""
from __future__ import annotations

import argparse
import csv
import datetime
import os
import re
import sys
from typing import Iterator

URL_KNOTS = "https://knotinfo.org/"
URL_LINKS = "https://link-info-repo.onrender.com/"
URL_PACKAGE = "https://github.com/soehms/database_knotinfo"


def read_table(path: str) -> Iterator[dict[str, str]]:
    csv.field_size_limit(sys.maxsize)
    with open(path, newline="", encoding="utf-8") as fh:
        rows = csv.reader(fh, delimiter="|")
        head = next(rows)
        next(rows)  # the descriptions ("Name", "PD Notation", ...)
        for row in rows:
            yield dict(zip(head, row))


def ints(text: str) -> list[int]:
    return [int(x) for x in re.findall(r"-?\d+", text)]


def conway_alexander(vector: str, name: str) -> list[int]:
    """KnotInfo's '[lo, hi, c_lo, ..., c_hi]' (powers of t) -> symmetric
    coefficients with Delta(1) = 1."""
    v = ints(vector)
    if len(v) == 1:  # the unknot: '1'
        return v
    lo, hi, coef = v[0], v[1], v[2:]
    if len(coef) != hi - lo + 1 or coef != coef[::-1]:
        raise SystemExit(f"{name}: Alexander vector {vector!r} is not symmetric")
    s = sum(coef)
    if s not in (1, -1):
        raise SystemExit(f"{name}: Alexander polynomial at 1 is {s}, not +-1")
    return [s * c for c in coef]


def determinant(coef: list[int]) -> int:
    h = (len(coef) - 1) // 2
    return abs(sum(c * (-1) ** abs(k - h) for k, c in enumerate(coef)))


def braid_word(text: str, name: str) -> list[int]:
    """KnotInfo's braid notation: '[1,1,1]', or for a few knots (10_136,
    11n_8, ...) two braids '[[...],[...]]', of which the first (on the
    fewest strands) is kept."""
    t = text.strip()
    if t.startswith("[["):
        t = t[1:t.index("]") + 1]
    return ints(t)


def closure_components(strands: int, word: list[int]) -> int:
    perm = list(range(strands))
    for g in word:
        i = abs(g) - 1
        perm[i], perm[i + 1] = perm[i + 1], perm[i]
    seen, cycles = set(), 0
    for p in range(strands):
        if p not in seen:
            cycles += 1
            while p not in seen:
                seen.add(p)
                p = perm[p]
    return cycles


def pd_text(pd: list[int], name: str) -> str:
    if len(pd) % 4:
        raise SystemExit(f"{name}: PD code of {len(pd)} numbers")
    return ";".join(",".join(str(x) for x in pd[i:i + 4]) for i in range(0, len(pd), 4))


def header(out, what: str, url: str, version: str, columns: list[str], extra: list[str]) -> None:
    today = datetime.date.today().isoformat()
    out.write(f"# {what}, extracted by scripts/knotinfo_extract.py on {today}\n")
    out.write(f"# Source: {url} through the Python package database_knotinfo {version} ({URL_PACKAGE})\n")
    out.write("# License: GPL-3.0 (database_knotinfo); Tightrope is GPL-3.0-or-later\n")
    out.write("# Cite: C. Livingston and A. H. Moore, KnotInfo: Table of Knot Invariants; LinkInfo: Table of Link "
              "Invariants\n")
    for line in extra:
        out.write(f"# {line}\n")
    out.write("\t".join(columns) + "\n")


def write_knots(src: str, dst: str, version: str, max_cross: int) -> int:
    cols = ["name", "crossings", "braid", "pd", "alexander", "determinant", "signature", "ropelength"]
    n = 0
    with open(dst + ".tmp", "w", encoding="utf-8") as out:
        header(out, f"Prime knots to {max_cross} crossings (KnotInfo)", URL_KNOTS, version, cols, [
            "braid: generators 1..s-1 separated by ',' (-i the inverse); pd: crossings X[a,b,c,d] separated by ';'",
            "alexander: Conway-normalised (Delta(1) = 1) coefficients of t^-h .. t^h; determinant = |Delta(-1)|",
            "ropelength: KnotInfo's (empty where none)"])
        for r in read_table(os.path.join(src, "knotinfo_data_complete.csv")):
            c = int(r["crossing_number"])
            if c > max_cross:
                continue
            name = r["name"]
            alex = conway_alexander(r["alexander_polynomial_vector"], name)
            det = determinant(alex)
            # KnotInfo lists 0 for the unknot's determinant; |Delta(-1)| = 1
            if c > 0 and int(r["determinant"]) != det:
                raise SystemExit(f"{name}: determinant {r['determinant']} but |Delta(-1)| = {det}")
            word = braid_word(r["braid_notation"], name)
            if c > 0 and (not word or closure_components(max(abs(g) for g in word) + 1, word) != 1):
                raise SystemExit(f"{name}: no braid word of one component in {r['braid_notation']!r}")
            braid = ",".join(str(x) for x in word)
            pd = pd_text(ints(r["pd_notation"]), name)
            out.write("\t".join([name, str(c), braid, pd, ",".join(map(str, alex)), str(det),
                                 r["signature"].strip(), r["ropelength"].strip()]) + "\n")
            n += 1
    os.replace(dst + ".tmp", dst)
    return n


def write_links(src: str, dst: str, version: str, max_cross: int) -> int:
    cols = ["name", "unoriented", "rolfsen", "components", "crossings", "strands", "braid", "pd", "determinant",
            "linking"]
    n = 0
    with open(dst + ".tmp", "w", encoding="utf-8") as out:
        header(out, f"Prime links to {max_cross} crossings (LinkInfo), every orientation", URL_LINKS, version, cols, [
            "braid: on 'strands' strands, generators as for knots; pd: as for knots (LinkInfo's vector form)",
            "linking: the linking matrix's upper triangle, row by row, for LinkInfo's orientation"])
        for r in read_table(os.path.join(src, "linkinfo_data_complete.csv")):
            c = int(r["crossing_number"])
            if c > max_cross:
                continue
            name = r["name"]
            b = ints(r["braid_notation"])
            if len(b) < 2:
                raise SystemExit(f"{name}: no braid word")
            k = int(r["components"])
            if closure_components(b[0], b[1:]) != k:
                raise SystemExit(f"{name}: its braid's closure does not have {k} components")
            lm = ints(r["linking_matrix"])
            if len(lm) != k * k:
                raise SystemExit(f"{name}: linking matrix of {len(lm)} numbers for {k} components")
            upper = [lm[i * k + j] for i in range(k) for j in range(i + 1, k)]
            out.write("\t".join([name, r["name_unoriented"], r["rolfsen_name"].strip(), str(k), str(c), str(b[0]),
                                 ",".join(map(str, b[1:])), pd_text(ints(r["pd_notation_vector"]), name),
                                 r["determinant"].strip(), ",".join(map(str, upper))]) + "\n")
            n += 1
    os.replace(dst + ".tmp", dst)
    return n


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv_dir")
    ap.add_argument("--version", default="2026.11.2", help="database_knotinfo's version (for the header)")
    ap.add_argument("--max-knot", type=int, default=12)
    ap.add_argument("--max-link", type=int, default=9)
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "knots"))
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    nk = write_knots(a.csv_dir, os.path.join(a.out, "knotinfo_knots.tsv"), a.version, a.max_knot)
    nl = write_links(a.csv_dir, os.path.join(a.out, "linkinfo_links.tsv"), a.version, a.max_link)
    print(f"{nk} knots, {nl} oriented links")


if __name__ == "__main__":
    main()
