"""The Python package against closed forms, the command line's own output
and the errors a user meets. The command line (for the measure --json
comparison) is $TIGHTROPE_CLI or `tightrope` on PATH; without it those
tests are skipped."""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Iterator, List, Tuple

import numpy as np
import pytest

import tightrope

IDEAL_TREFOIL = 32.7429  # Przybyl & Pieranski: no trefoil of thickness 1 is shorter
# (nor, as far as any computation has found, any knotted curve)
IDEAL_HOPF = 8 * math.pi  # closed form: two round circles of radius 2, each through the other's centre
TREFOIL_PD = [(1, 5, 2, 4), (3, 1, 4, 6), (5, 3, 6, 2)]  # KnotTheory's PD[3_1]
DEVICE = "reference"  # the serial engine: the same on every machine


def cli() -> str:
    exe = os.environ.get("TIGHTROPE_CLI") or shutil.which("tightrope")
    if not exe:
        pytest.skip("no tightrope command line (TIGHTROPE_CLI) to compare with")
    return exe


def test_import_and_version() -> None:
    """The version is the project's (CMakeLists.txt); the library, opened on
    first use, is looked for at import: a TIGHTROPE_LIBRARY that names no
    file is an ImportError there, not a failure at the first call."""
    cmake = Path(__file__).resolve().parents[2] / "CMakeLists.txt"
    want = re.search(r"project\(tightrope VERSION ([0-9.]+)", cmake.read_text())
    assert want is not None and tightrope.__version__ == tightrope.version() == want.group(1)
    env = dict(os.environ, TIGHTROPE_LIBRARY="/nonexistent/libtightrope.so")
    r = subprocess.run([sys.executable, "-c", "import tightrope"], env=env, capture_output=True, text=True)
    assert r.returncode != 0 and "ImportError: tightrope: TIGHTROPE_LIBRARY=/nonexistent/libtightrope.so: no such file" in r.stderr


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
    # KnotInfo's 7_4 from its minimal diagram or braid, at thickness 1.25 (the
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
    # the start's ropelength it compares with is the measure's of the start
    assert r.start_ropelength == pytest.approx(tightrope.measure(start)["ropelength"], rel=1e-12)
    assert r.kkt_residual is not None and 0 <= r.kkt_residual < 1
    assert not r.interrupted and r.stopped in {"residual", "jammed", "time-limit", "solved"}
    assert seen and all(p.n == 64 for p in seen)


def test_progress_exception_stops_the_run() -> None:
    def boom(p: tightrope.Progress) -> None:
        raise ValueError("stop here")

    t0 = time.monotonic()
    with pytest.raises(ValueError, match="stop here"):
        # one road: the automatic roads' first seconds compact the start, and
        # a compaction reports no progress (a Ctrl-C stops it: the test below)
        tightrope.tighten(tightrope.make_knot("trefoil", n=400), time_limit=60, device=DEVICE, progress=boom, progress_every=0.05, tries=1)
    assert time.monotonic() - t0 < 15


@pytest.fixture
def python_sigint() -> Iterator[None]:
    """Python's own SIGINT handler for the test's length.

    A process started in the background of a non-interactive shell (`nohup CMD &`, as a CI
    may start its suite) begins with SIGINT ignored, Python keeps it so, and a SIGINT then
    reaches nothing: the CI's "not interrupted (signal sent, run solved 26 s later)". A user
    who ignores SIGINT keeps it ignored; the test sets the handler it is about."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)


def test_ctrl_c_keeps_the_best_state(python_sigint: None) -> None:
    """SIGINT during a run raises KeyboardInterrupt within a second; the best state comes with it."""
    # The signal is sent once the run has reported a rope shorter than the
    # start's: a timer at a fixed second landed before that on a loaded CI
    # machine (the coarse level still longer than the start) and after the
    # whole run on an idle one.
    start = tightrope.make_knot("trefoil", n=800)
    l0 = tightrope.measure(start)["ropelength"]
    sent: List[float] = []
    seen: List[tightrope.Progress] = []

    def interrupt() -> None:
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    def watch(p: tightrope.Progress) -> None:
        seen.append(p)
        if p.ropelength < l0 and not sent:
            sent.append(float("nan"))  # armed; the timer records the time
            threading.Timer(0.0, interrupt).start()

    # one road (tries=1): with a time limit of 50 s or more a loose start
    # takes the automatic roads, whose first seconds compact the start.
    # Not interrupted (seen twice on loaded machines): say what the run
    # reported, so that the next failure tells why.
    with pytest.raises(KeyboardInterrupt) as e:
        r0 = tightrope.tighten(start, time_limit=120, device=DEVICE, kkt=False, tries=1, progress=watch, progress_every=0.05)
        shortest = min((p.ropelength for p in seen), default=float("nan"))
        pytest.fail(
            f"not interrupted: {len(seen)} progress reports, the shortest {shortest:.6f} against the start's {l0:.6f}, "
            f"signal {'sent' if len(sent) == 2 else 'armed' if sent else 'never armed'}; the run stopped "
            f"{r0.stopped} at N {r0.n} after {r0.elapsed:.2f} s"
        )
    assert len(sent) == 2 and time.monotonic() - sent[1] < 1.0
    assert isinstance(e.value, tightrope.Interrupted)
    r = e.value.result
    assert r is not None and r.interrupted and r.stopped == "signal"
    # the state kept is the run's at the stop, not an older one: within 1e-3 of the
    # level's last report (the reports are the backend's estimate, the result the
    # oracle's measure at thickness 1; the steps after the report move it a little)
    level = [p.ropelength for p in seen if p.n == r.n]
    assert level and r.ropelength <= level[-1] * (1 + 1e-3)
    assert isinstance(r.curve, np.ndarray) and r.curve.shape == (r.n, 3) and r.ropelength < l0
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


# ---------------------------------------------------------------- Links and PD codes where a curve is
#
# The knot type of a curve, found here independently of the library (which
# checks it with its own Alexander polynomials): the crossings of a generic
# projection give the knot's determinant |Alexander(-1)| from the Fox
# colouring matrix (Livingston, Knot Theory, 3.3; 1 for the unknot, 3 for
# the trefoil, 5 for the figure eight) and a two-component link's linking
# number (half the signed crossings between the components).


def _crossings(comps: List[np.ndarray]) -> List[Tuple[int, float, int, float, int]]:
    """(over component, over position, under component, under position,
    sign) per crossing of the projection along a generic direction; a
    position is edge index + parameter along the edge."""
    d = np.array([0.2358, 0.4617, 0.8552])  # generic: no vertex over an edge
    d /= np.linalg.norm(d)
    e1 = np.cross(d, [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(d, e1)
    frame = np.stack([e1, e2, d], axis=1)
    start = np.concatenate([c @ frame for c in comps])  # every edge, in the frame (e1, e2, d)
    step = np.concatenate([np.roll(c, -1, axis=0) @ frame - c @ frame for c in comps])
    comp = np.concatenate([np.full(len(c), k) for k, c in enumerate(comps)])
    index = np.concatenate([np.arange(len(c)) for c in comps])
    size = np.concatenate([np.full(len(c), len(c)) for c in comps])
    out = []
    for a in range(len(start) - 1):  # edge a against every later edge b at once
        b = np.arange(a + 1, len(start))
        den = step[a, 0] * step[b, 1] - step[a, 1] * step[b, 0]
        w = start[b] - start[a]
        with np.errstate(divide="ignore", invalid="ignore"):
            s = (w[:, 0] * step[b, 1] - w[:, 1] * step[b, 0]) / den
            t = (w[:, 0] * step[a, 1] - w[:, 1] * step[a, 0]) / den
        neighbours = (comp[b] == comp[a]) & np.isin((index[b] - index[a]) % size[a], (1, size[a] - 1))
        hit = (den != 0) & ~neighbours & (s >= 0) & (s < 1) & (t >= 0) & (t < 1)
        for j, sj, tj, dj in zip(b[hit], s[hit], t[hit], den[hit]):
            za, zb = start[a, 2] + sj * step[a, 2], start[j, 2] + tj * step[j, 2]
            sign = int(np.sign(dj))
            if za > zb:
                out.append((int(comp[a]), index[a] + sj, int(comp[j]), index[j] + tj, sign))
            else:
                out.append((int(comp[j]), index[j] + tj, int(comp[a]), index[a] + sj, -sign))
    return out


def knot_determinant(curve: np.ndarray) -> int:
    """|det| of the colouring matrix with one row and column struck out."""
    cr = _crossings([curve])
    under = sorted(c[3] for c in cr)
    n = len(under)
    if n < 2:
        return 1
    m = np.zeros((n, n))
    for _, over, _, pos, _ in cr:
        k = under.index(pos)  # the under-arc k ends here, k + 1 starts
        o = sum(u < over for u in under) % n  # the arc passing over
        m[k, o] += 2
        m[k, k] -= 1
        m[k, (k + 1) % n] -= 1
    return abs(round(float(np.linalg.det(m[1:, 1:]))))


def linking_number(link: List[np.ndarray]) -> int:
    assert len(link) == 2
    return abs(sum(c[4] for c in _crossings(link) if c[0] != c[2])) // 2


class StandInLink:
    """What a spherogram/SnapPy Link offers tightrope: its braid word."""

    def __init__(self, word: List[int]) -> None:
        self.word = word

    def braid_word(self) -> List[int]:
        return self.word


def test_knot_type_helpers_on_known_curves() -> None:
    """The independent type checks against the published determinants and linking number."""
    assert knot_determinant(tightrope.make_knot("circle")) == 1
    assert knot_determinant(tightrope.make_knot("trefoil", n=90)) == 3
    assert knot_determinant(tightrope.make_knot("braid 1,-2,1,-2")) == 5
    assert knot_determinant(tightrope.make_knot("5_1")) == 5
    assert linking_number(tightrope.make_link("hopf")) == 1


def test_measure_takes_a_link_or_a_pd_code() -> None:
    """A PD code or a Link is measured as the start make_knot makes of it:
    of its type, at thickness >= 1, looser than the ideal trefoil."""
    for knot, det in ((TREFOIL_PD, 3), (StandInLink([1, -2, 1, -2]), 5)):
        m = tightrope.measure(knot)
        start = tightrope.make_knot(knot)
        assert m == tightrope.measure(start)
        assert m["components"] == 1 and m["vertices"] == len(start)
        assert m["thickness"] >= 1.0 and m["ropelength"] > IDEAL_TREFOIL
        assert knot_determinant(start) == det
    hopf = tightrope.measure(StandInLink([1, 1]))  # a braid closing to two components: a link
    assert hopf["components"] == 2 and hopf["ropelength"] > IDEAL_HOPF
    assert tightrope.measure(tuple(TREFOIL_PD)) == tightrope.measure(TREFOIL_PD)
    # spherogram numbers a PD code's edges from 0, KnotTheory from 1: the same code
    assert tightrope.measure([tuple(v - 1 for v in c) for c in TREFOIL_PD]) == tightrope.measure(TREFOIL_PD)
    # a name is not a curve (it could be a file's): make_knot or read says which
    with pytest.raises(tightrope.Error, match="not a curve: make_knot"):
        tightrope.measure("trefoil")
    # a PD code the library refuses, with its message
    with pytest.raises(tightrope.Error, match="appears 3 times"):
        tightrope.measure([(1, 5, 2, 4), (3, 1, 4, 6), (5, 3, 5, 2)])


def test_tighten_and_analyze_take_a_link_or_a_pd_code() -> None:
    """A short tighten from a PD code keeps the trefoil (determinant 3) and
    stays above the ideal; from a Link closing to two components, a link
    comes back (a list), linked once, above the Hopf link's 8 pi."""
    # 100 steps at a given n, not a time limit: the same run on any machine
    # (2 s under the sanitizers' leg of CI once ended on the coarse level
    # above the start; without n the automatic roads' scouts share the time
    # limit, and under the sanitizers on a loaded CI machine one such run
    # ended at 64.3 from a start of 35.6)
    loose = tightrope.measure(TREFOIL_PD)["ropelength"]
    r = tightrope.tighten(TREFOIL_PD, n=96, steps=100, time_limit=120, device=DEVICE, kkt=False)
    assert isinstance(r.curve, np.ndarray) and r.curve.shape[1] == 3
    assert knot_determinant(r.curve) == 3
    assert IDEAL_TREFOIL < r.ropelength < loose
    h = tightrope.tighten(StandInLink([1, 1]), n=96, steps=100, time_limit=120, device=DEVICE, kkt=False)
    assert isinstance(h.curve, list) and len(h.curve) == 2
    assert linking_number(h.curve) == 1
    assert IDEAL_HOPF < h.ropelength < tightrope.measure(StandInLink([1, 1]))["ropelength"]
    # analyze: the start's profiles, at thickness 1 (curvature <= 1 / MinRad <= 1)
    a = tightrope.analyze(StandInLink([1, 1, 1]))
    b = tightrope.analyze(tightrope.make_knot(StandInLink([1, 1, 1])))
    assert np.array_equal(a.curvature, b.curvature) and a.curvature.max() <= 1 + 1e-9


def test_spherogram_links_and_their_pd_codes() -> None:
    """The real thing, where spherogram is installed: a Link and its own
    (0-based) PD code give starts of the knot's published determinant
    (3_1: 3, 4_1: 5, 5_2: 7); its Hopf link is linked once."""
    spherogram = pytest.importorskip("spherogram")
    for name, det in (("3_1", 3), ("4_1", 5), ("5_2", 7)):
        link = spherogram.Link(name)
        assert tightrope.measure(link)["components"] == 1
        assert knot_determinant(tightrope.make_knot(link)) == det
        assert knot_determinant(tightrope.make_knot(link.PD_code())) == det
    hopf = tightrope.make_link(spherogram.Link("L2a1"))
    assert len(hopf) == 2 and linking_number(hopf) == 1
