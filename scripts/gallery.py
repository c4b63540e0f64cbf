#!/usr/bin/env python3
"""A batch's results as a data release: the table, the tight curves (xz), a tube picture per knot
and one HTML page (issue 47 item 4).

    scripts/gallery.py BATCH_OUT -o RELEASE [--tightrope PATH] [--title TEXT] [--tube-size PX]

BATCH_OUT is a `tightrope batch` folder (its table.tsv and NAME.vect); RELEASE, which must not
exist, gets table.tsv and table.json (the batch's, as they are), curves/NAME.vect.xz,
pictures/NAME.png (`tightrope analyze NAME.vect --plots`: the front view of the tube, radius 1,
contacts marked) and index.html, one row a knot. RELEASE is made beside itself under another name
and renamed into place last: a failed or interrupted run leaves no RELEASE, and nothing in
BATCH_OUT is written. The page needs no script to show; a few lines mark each picture
`data-shown="1"` once the browser has drawn it (tests/scripts/gallery_cli.sh reads that
back from a headless browser).
"""
from __future__ import annotations

import argparse
import csv
import html
import lzma
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Dict, List, Optional

NAME_CHARS = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._+-")
NAME_MAX = 200  # batch's own rule (host/cli/batch_manifest.c, tr_batch_name_ok)


def batch_name_ok(name: str) -> bool:
    return 0 < len(name) <= NAME_MAX and name[0] not in ".-" and set(name) <= NAME_CHARS


class GalleryError(Exception):
    """A one-line reason, naming the file."""


def read_table(path: Path) -> List[Dict[str, str]]:
    """The batch's table.tsv, one dict a knot, columns by the header's names."""
    rows: List[Dict[str, str]] = []
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f, delimiter="\t", quoting=csv.QUOTE_NONE)
            for row in reader:
                for col in ("knot", "N", "ropelength"):
                    if not row.get(col):
                        raise GalleryError(f"{path}:{reader.line_num}: no '{col}' (not a tightrope batch table)")
                if not batch_name_ok(row["knot"]):
                    raise GalleryError(f"{path}:{reader.line_num}: knot name '{row['knot']}' is not a batch name")
                for col in ("ropelength", "diff"):
                    if row.get(col, "-") not in ("", "-"):
                        try:
                            float(row[col])
                        except ValueError:
                            raise GalleryError(f"{path}:{reader.line_num}: {col} '{row[col]}' is not a number") from None
                rows.append(row)
    except OSError as e:
        raise GalleryError(f"{path}: cannot read ({e.strerror})") from None
    except UnicodeDecodeError:
        raise GalleryError(f"{path}: not UTF-8 text (not a tightrope batch table)") from None
    if not rows:
        raise GalleryError(f"{path}: no knots in the table")
    return rows


def tube_picture(tightrope: str, curve: Path, work: Path, size: int) -> Path:
    """The front view of the curve's tube, drawn by `tightrope analyze --plots` into work."""
    try:
        run = subprocess.run(
            # the curve's absolute path: a name never reads as an option
            [tightrope, "analyze", str(curve.resolve()), "--out", str(work), "--plots", "--tube-size", str(size)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
    except OSError as e:
        raise GalleryError(f"{tightrope}: cannot run ({e.strerror})") from None
    if run.returncode != 0:
        last = run.stderr.strip().splitlines()[-1:] or ["no message"]
        raise GalleryError(f"{curve}: tightrope analyze failed: {last[0]}")
    # one folder per component for a link; the first component's front view stands for it
    found = sorted(work.rglob("tube_front.png"))
    if not found:
        raise GalleryError(f"{curve}: tightrope analyze drew no tube_front.png (is gnuplot installed?)")
    return found[0]


def number(text: str, digits: int) -> str:
    try:
        v = float(text)
    except ValueError:
        return "-" if text in ("", "-") else html.escape(text)
    return "-" if v != v else f"{v:.{digits}f}"


def pct(text: Optional[str]) -> str:
    return "-" if text in (None, "", "-") else html.escape(text) + " %"


def page(rows: List[Dict[str, str]], title: str, has_json: bool) -> str:
    has_ref = any(r.get("ref_ropelength", "-") not in ("", "-") for r in rows)
    at_or_below = sum(1 for r in rows if r.get("diff", "-") not in ("", "-") and float(r["diff"]) <= 0)
    head = ["", "knot", "N", "ropelength", "KKT residual", "type"] + (["reference", "difference"] if has_ref else [])
    out = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{html.escape(title)}</title>",
        "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
        "td,th{padding:4px 10px;border-bottom:1px solid #ddd;text-align:right}"
        "td.name,th.name{text-align:left}img{width:180px;height:180px}</style>",
        "</head><body>",
        f"<h1>{html.escape(title)}</h1>",
        f"<p>{len(rows)} knots, tightened by tightrope; ropelength = length / radius of the polygon at thickness 1, "
        "measured on the written curve. " + (f"{at_or_below} of {len(rows)} at or below the reference. " if has_ref else "")
        + 'The table: <a href="table.tsv">table.tsv</a>'
        + (', <a href="table.json">table.json</a>' if has_json else "") + ".</p>",
        '<table id="knots"><thead><tr>' + "".join(
            f'<th class="name">{h}</th>' if h == "knot" else f"<th>{h}</th>" for h in head) + "</tr></thead><tbody>",
    ]
    for r in rows:
        k = html.escape(r["knot"])
        cells = [
            f'<td><img src="pictures/{k}.png" alt="{k}, tight" data-knot="{k}"></td>',
            f'<td class="name"><a href="curves/{k}.vect.xz">{k}</a></td>',
            f"<td>{html.escape(r['N'])}</td>",
            f"<td>{number(r['ropelength'], 6)}</td>",
            f"<td>{html.escape(r.get('kkt_residual', '-') or '-')}</td>",
            f"<td>{html.escape(r.get('type_check', '-') or '-')}</td>",
        ]
        if has_ref:
            cells += [f"<td>{number(r.get('ref_ropelength', '-'), 4)}</td>",
                      f"<td>{pct(r.get('diff_pct', '-'))}</td>"]
        out.append(f'<tr id="knot-{k}">' + "".join(cells) + "</tr>")
    out += [
        "</tbody></table>",
        # marks what the browser drew (tests read it back; a reader sees nothing of it)
        "<script>window.addEventListener('load',()=>{for(const i of document.images)"
        "i.dataset.shown=(i.complete&&i.naturalWidth>0)?'1':'0';document.body.dataset.checked='1';});</script>",
        "</body></html>",
        "",
    ]
    return "\n".join(out)


def make(batch: Path, release: Path, tightrope: str, title: str, size: int) -> int:
    table = batch / "table.tsv"
    rows = read_table(table)
    if release.resolve().is_relative_to(batch.resolve()):
        raise GalleryError(f"{release}: inside the batch folder {batch}, which is read only here")
    parent = release.resolve().parent
    if not parent.is_dir():
        raise GalleryError(f"{release}: no folder {parent}")
    # the name claimed first (mkdir fails where anything is), so that the
    # rename at the end replaces only the empty folder made here
    try:
        os.mkdir(release)
    except FileExistsError:
        raise GalleryError(f"{release}: exists; the release is written to a new folder only") from None
    except OSError as e:
        raise GalleryError(f"{release}: cannot make it ({e.strerror})") from None
    tmp: Optional[Path] = None
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{release.name}.", dir=parent))
        (tmp / "curves").mkdir()
        (tmp / "pictures").mkdir()
        for name in ("table.tsv", "table.json"):
            if (batch / name).is_file():
                shutil.copyfile(batch / name, tmp / name)
        for r in rows:
            k = r["knot"]
            curve = batch / f"{k}.vect"
            if not curve.is_file():
                raise GalleryError(f"{table}: knot {k} has no curve {curve}")
            with open(curve, "rb") as f, lzma.open(tmp / "curves" / f"{k}.vect.xz", "wb") as z:
                shutil.copyfileobj(f, z)
            with tempfile.TemporaryDirectory(dir=tmp) as work:
                shutil.copyfile(tube_picture(tightrope, curve, Path(work) / "a", size), tmp / "pictures" / f"{k}.png")
            print(f"gallery: {k}", file=sys.stderr)
        (tmp / "index.html").write_text(page(rows, title, (tmp / "table.json").is_file()), encoding="utf-8")
        os.chmod(tmp, 0o755)
        os.rmdir(release)
        os.rename(tmp, release)
    except OSError as e:
        cleanup(tmp, release)
        raise GalleryError(f"{e.filename or release}: {e.strerror}") from None
    except BaseException:
        cleanup(tmp, release)
        raise
    print(f"gallery: {release}/index.html: {len(rows)} knots")
    return 0


def cleanup(tmp: Optional[Path], release: Path) -> None:
    """What this run made, removed: the folder it was building, the name it claimed (if still empty)."""
    if tmp is not None:
        shutil.rmtree(tmp, ignore_errors=True)
    try:
        os.rmdir(release)
    except OSError:
        pass


def on_signal(signum: int, frame: object) -> None:
    raise KeyboardInterrupt


def default_tightrope() -> str:
    here = Path(__file__).resolve().parent.parent / "build" / "tightrope"
    return str(here) if here.is_file() else (shutil.which("tightrope") or "tightrope")


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("batch", type=Path, help="a tightrope batch output folder")
    ap.add_argument("-o", "--output", type=Path, required=True, help="the release folder (must not exist)")
    ap.add_argument("--tightrope", default=default_tightrope(), help="the tightrope program (default: build/tightrope)")
    ap.add_argument("--title", default="Tight knots", help="the page's title")
    ap.add_argument("--tube-size", type=int, default=360, help="the pictures' size in pixels (200 to 4000)")
    a = ap.parse_args(argv)
    if not 200 <= a.tube_size <= 4000:
        ap.error(f"--tube-size {a.tube_size}: 200 to 4000 pixels")
    # a terminal closed or a job killed is an interrupt too: the folder being made is removed
    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGHUP, on_signal)
    try:
        return make(a.batch, a.output, a.tightrope, a.title, a.tube_size)
    except GalleryError as e:
        print(f"gallery: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("gallery: interrupted; no release written", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
