"""The Python package against closed forms, the command line's own output
and the errors a user meets. The command line (for the measure --json
comparison) is $TIGHTROPE_CLI or `tightrope` on PATH; without it those
tests are skipped."""

from __future__ import annotations

import json
import math
import os
import shutil
import signal
import subprocess
import threading
import time
from pathlib import Path
from typing import List

import numpy as np
import pytest

import tightrope

IDEAL_TREFOIL = 32.7429  # Przybyl & Pieranski: no trefoil of thickness 1 is shorter
DEVICE = "reference"  # the serial engine: the same on every machine


def cli() -> str:
    exe = os.environ.get("TIGHTROPE_CLI") or shutil.which("tightrope")
    if not exe:
        pytest.skip("no tightrope command line (TIGHTROPE_CLI) to compare with")
    return exe


def test_make_knot_and_link() -> None:
    k = tightrope.make_knot("torus 2 3", n=120)
    assert isinstance(k, np.ndarray) and k.shape == (120, 3) and k.dtype == np.float64
    assert np.array_equal(tightrope.make_knot("trefoil", n=120), k)
    assert tightrope.make_knot("circle").shape == (64, 3)
    hopf = tightrope.make_link("hopf", n=32)
    assert len(hopf) == 2 and all(c.shape == (32, 3) for c in hopf)
    clasp = tightrope.Curve.make("clasp", 40)
    assert clasp.closed == [False, False] and clasp.constraints == 4
    with pytest.raises(tightrope.Error, match="no knot or link named"):
        tightrope.make_knot("no-such-knot")


def test_make_by_name() -> None:
    # KnotInfo's 7_4 as the closure of its braid, at thickness 1.25 (the
    # oracle's), its type checked in C against the table's invariants
    k = tightrope.make_knot("7_4")
    assert k.ndim == 2 and k.shape[1] == 3
    assert tightrope.measure(k)["thickness"] >= 1.0
    borromean = tightrope.make_link("L6a4")
    assert len(borromean) == 3
    with pytest.raises(tightrope.Error, match="nearest: 7_4"):
        tightrope.make_knot("7_44")
    with pytest.raises(tightrope.Error, match="make_link"):
        tightrope.make_knot("L6a4")


def test_make_from_notation() -> None:
    # the trefoil's PD code (KnotTheory's convention; the library checks the
    # laid-out curve against the code's own Alexander polynomial and
    # signature) and the figure eight's braid word give ropes at thickness
    # >= 1; a braid of two cycles gives two components; a PD code that is not
    # a diagram is refused with the library's message
    pd = [(1, 5, 2, 4), (3, 1, 4, 6), (5, 3, 6, 2)]
    trefoil = tightrope.make_knot(pd)
    assert trefoil.ndim == 2 and tightrope.measure(trefoil)["thickness"] >= 1.0
    eight = tightrope.make_knot("braid 1,-2,1,-2")
    assert tightrope.measure(eight)["thickness"] >= 1.0
    assert len(tightrope.make_link("braid 1,1")) == 2
    with pytest.raises(tightrope.Error, match="appears 3 times"):
        tightrope.make_knot([(1, 5, 2, 4), (3, 1, 4, 6), (5, 3, 5, 2)])

    class FakeLink:  # what spherogram.Link offers
        def braid_word(self) -> List[int]:
            return [1, 1, 1]

    assert tightrope.make_knot(FakeLink()).shape[1] == 3
    with pytest.raises(tightrope.Error, match="make_link"):
        tightrope.make_knot("hopf")


def test_circle_closed_form() -> None:
    """A regular 64-gon of radius 4: MinRad = thickness = R cos(pi/n), length 2 n R sin(pi/n)."""
    m = tightrope.measure(tightrope.make_knot("circle 4", n=64))
    t = math.pi / 64
    assert m["components"] == 1 and m["vertices"] == 64
    assert m["length"] == pytest.approx(2 * 64 * 4 * math.sin(t), rel=1e-14)
    assert m["thickness"] == pytest.approx(4 * math.cos(t), rel=1e-14)
    assert m["ropelength"] == pytest.approx(2 * 64 * math.tan(t), rel=1e-14)
    assert m["per_component"][0]["closed"] is True


@pytest.mark.parametrize("spec", [["torus", "2", "3", "--n", "90"], ["hopf", "--n", "40"], ["clasp", "--n", "30"]])
def test_measure_agrees_with_cli(tmp_path: Path, spec: List[str]) -> None:
    """Every key and number of `tightrope measure --json --kkt`, to the last digit."""
    exe = cli()
    f = tmp_path / "c.vect"
    subprocess.run([exe, "make", *spec, "-o", str(f)], check=True, capture_output=True)
    want = json.loads(subprocess.run([exe, "measure", "--json", "--kkt", str(f)], check=True, capture_output=True, text=True).stdout)
    del want["file"]
    got = tightrope.measure(tightrope.read(f), kkt=True)
    assert got == want
    # the arrays alone (no constraints): the same numbers where the file has none
    if spec[0] != "clasp":
        c = tightrope.read(f).components
        assert tightrope.measure(c if len(c) > 1 else c[0]) == {k: v for k, v in want.items() if k != "kkt"}


def test_files_round_trip(tmp_path: Path) -> None:
    k = tightrope.make_knot("torus 3 2", n=90) * (1 + 1e-13)
    tightrope.write(tmp_path / "k.vect", k, comments="round trip")
    back = tightrope.read(tmp_path / "k.vect").components[0]
    assert np.array_equal(back, k)  # %.17g: exact
    c = tightrope.Curve.make("clasp", 30)
    c.write(tmp_path / "clasp.vect")
    assert tightrope.read(tmp_path / "clasp.vect").constraints == 4


def figure_eight_in_plane() -> np.ndarray:
    """A curve through itself: vertices 0 and 100 both at the origin."""
    t = 2 * np.pi * np.arange(200) / 200
    return np.stack([15 * np.sin(t), 15 * np.sin(t) * np.cos(t), np.zeros_like(t)], axis=1)


def test_errors_carry_the_library_message() -> None:
    with pytest.raises(tightrope.Error, match="has 2 vertices, needs at least 3"):
        tightrope.measure(np.array([[0.0, 0, 0], [1, 0, 0]]))
    bad = tightrope.make_knot("circle")
    bad[5, 1] = np.nan
    with pytest.raises(tightrope.Error, match="vertex 5 of component 0 is not finite"):
        tightrope.measure(bad)
    with pytest.raises(tightrope.Error, match="passes through itself"):
        tightrope.measure(figure_eight_in_plane())
    with pytest.raises(tightrope.Error, match="passes through itself") as e:
        tightrope.tighten(figure_eight_in_plane(), time_limit=1, device=DEVICE)
    assert e.value.status == -5
    with pytest.raises(tightrope.Error, match=r"\(N, 3\)"):
        tightrope.measure(np.zeros((10, 2)))
    with pytest.raises(tightrope.Error):
        tightrope.read("/nonexistent/k.vect")
    with pytest.raises(TypeError, match="no_such_option"):
        tightrope.tighten(tightrope.make_knot("trefoil"), no_such_option=1)


def test_tighten_trefoil() -> None:
    start = tightrope.make_knot("trefoil", n=64)
    seen: List[tightrope.Progress] = []
    r = tightrope.tighten(start, time_limit=2, device=DEVICE, progress=seen.append, progress_every=0.05)
    assert isinstance(r.curve, np.ndarray) and r.curve.shape == (64, 3)
    m = tightrope.measure(r.curve)
    # what it says is what an independent measure of its curve finds
    assert m["ropelength"] == pytest.approx(r.ropelength, rel=1e-12)
    assert IDEAL_TREFOIL < r.ropelength < tightrope.measure(start)["ropelength"] - 1
    assert r.kkt_residual is not None and 0 <= r.kkt_residual < 1
    assert not r.interrupted and r.stopped in {"residual", "jammed", "time-limit", "solved"}
    assert seen and all(p.n == 64 for p in seen)


def test_progress_exception_stops_the_run() -> None:
    def boom(p: tightrope.Progress) -> None:
        raise ValueError("stop here")

    t0 = time.monotonic()
    with pytest.raises(ValueError, match="stop here"):
        tightrope.tighten(tightrope.make_knot("trefoil", n=400), time_limit=60, device=DEVICE, progress=boom, progress_every=0.05)
    assert time.monotonic() - t0 < 15


def test_ctrl_c_keeps_the_best_state() -> None:
    """SIGINT during a run raises KeyboardInterrupt within a second; the best state comes with it."""
    start = tightrope.make_knot("trefoil", n=400)
    l0 = tightrope.measure(start)["ropelength"]
    sent = []

    def interrupt() -> None:
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    threading.Timer(2.0, interrupt).start()
    with pytest.raises(KeyboardInterrupt) as e:
        tightrope.tighten(start, time_limit=120, device=DEVICE, kkt=False)
    assert time.monotonic() - sent[0] < 1.0
    assert isinstance(e.value, tightrope.Interrupted)
    r = e.value.result
    assert r is not None and r.interrupted and r.stopped == "signal"
    # an interrupt on the route's coarse level (N/4) keeps that level's curve
    assert r.curve.shape == (r.n, 3) and r.ropelength < l0
    assert tightrope.measure(r.curve)["ropelength"] == pytest.approx(r.ropelength, rel=1e-12)


def test_analyze_circle() -> None:
    """A circle at thickness 1: every inscribed arc has curvature 1 (1 / MinRad), no torsion."""
    a = tightrope.analyze(tightrope.make_knot("circle 7", n=48), m=1)
    assert a.curvature.shape == (48,) and a.torsion.shape == (48,)
    assert np.allclose(a.curvature, 1.0, rtol=0, atol=1e-12)
    assert np.all(np.abs(a.torsion) < 1e-9)
    assert np.all(np.diff(a.position) > 0)
    assert a.summary["vertices"] == 48 and a.contacts.shape[1] == 3


def test_analyze_tight_trefoil() -> None:
    r = tightrope.tighten(tightrope.make_knot("trefoil", n=100), time_limit=2, device=DEVICE)
    a = tightrope.analyze(r.curve)
    assert a.curvature.max() <= 1 + 1e-9  # MinRad >= thickness = 1
    assert len(a.contacts) > 0 and np.all(a.contacts[:, 2] >= 2 * (1 - 1e-9))  # struts no shorter than the diameter
    assert a.summary["component"] == 0 and "ropelength" in a.summary


def test_tighten_far_from_origin_reports_its_shift() -> None:
    """A start whose box misses the origin is tightened about it: curve + shift is where it was."""
    start = tightrope.make_knot("trefoil", n=64) + np.array([1000.0, 0.0, 0.0])
    r = tightrope.tighten(start, time_limit=1, device=DEVICE, kkt=False)
    assert r.shift.shape == (3,) and abs(r.shift[0] - 1000.0) < 10
    assert np.allclose((r.curve + r.shift).mean(axis=0), start.mean(axis=0), atol=5.0)
