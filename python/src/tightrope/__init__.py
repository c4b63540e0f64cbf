"""Tightrope from Python: make, measure, tighten and analyze knots, links and
clasps (ropes of radius 1 pulled tight), over the C library libtightrope.so.

    import tightrope
    k = tightrope.make_knot("trefoil", n=400)        # numpy (400, 3)
    r = tightrope.tighten(k, time_limit=10)          # r.curve, r.ropelength, r.kkt_residual
    tightrope.measure(r.curve)["ropelength"]

A curve is an (N, 3) array (one closed component), a list of them (a
link), or a tightrope.Curve (any components, open ropes and their
constraints, e.g. a clasp read from a file); measure, tighten and analyze
also take a spherogram/SnapPy Link or a PD code (a list of 4-tuples), made
into the start curve make_knot/make_link make (a name string is not a
curve: make_knot(name) says which is meant). Errors raise tightrope.Error
with the library's one-line message.
"""

from __future__ import annotations

import ctypes
import math
import os
import signal
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Dict, List, NamedTuple, Optional, Protocol, Sequence, Union, cast

import numpy as np

from . import _lib
from ._lib import lib

__all__ = [
    "Error",
    "Interrupted",
    "Curve",
    "Progress",
    "TightenResult",
    "Analysis",
    "make_knot",
    "make_link",
    "read",
    "write",
    "measure",
    "tighten",
    "analyze",
    "version",
]

__version__: str  # the library's, read when first asked for (module __getattr__)


def __getattr__(name: str) -> Any:
    if name == "__version__":
        return lib.tightrope_version().decode()
    raise AttributeError(f"module 'tightrope' has no attribute {name!r}")

if TYPE_CHECKING:  # numpy.typing only for the checker: import time (json too, imported where used)
    import numpy.typing as npt

    Array = npt.NDArray[np.float64]
else:
    Array = np.ndarray


class Error(Exception):
    """A failure the library reports: .status (a negative tightrope_status) and its one-line message."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status


def _check(rc: int, err: _lib.ErrorStruct) -> None:
    if rc != 0:
        msg = err.message.decode(errors="replace") or lib.tightrope_strerror(rc).decode()
        raise Error(rc, msg)


def version() -> str:
    """The library's version, e.g. "0.1.0"."""
    return str(lib.tightrope_version().decode())


class Curve:
    """A curve held by the library: one or more components, closed or open,
    with the constraints of a file or a start curve (a clasp's ends stay on
    their planes)."""

    def __init__(self, components: Union[npt.ArrayLike, Sequence[npt.ArrayLike]], closed: Union[bool, Sequence[bool]] = True) -> None:
        comps = _components(components)
        flags = [bool(closed)] * len(comps) if isinstance(closed, (bool, np.bool_)) else [bool(c) for c in closed]
        if len(flags) != len(comps):
            raise Error(-3, f"{len(comps)} components but {len(flags)} closed flags")
        xyz = np.ascontiguousarray(np.concatenate(comps) if comps else np.zeros((0, 3)), dtype=np.float64)
        offsets = (ctypes.c_size_t * (len(comps) + 1))(*np.cumsum([0] + [len(c) for c in comps]).tolist())
        cflags = (ctypes.c_int * max(1, len(comps)))(*[int(f) for f in flags])
        err = _lib.ErrorStruct()
        h = ctypes.c_void_p()
        rc = lib.tightrope_curve_new(len(comps), offsets, cflags, xyz.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), ctypes.byref(h), ctypes.byref(err))
        _check(rc, err)
        self._h = h

    @classmethod
    def _take(cls, h: ctypes.c_void_p) -> "Curve":
        c = cls.__new__(cls)
        c._h = h
        return c

    def __del__(self) -> None:
        h = getattr(self, "_h", None)
        if h:
            lib.tightrope_curve_free(h)
            self._h = ctypes.c_void_p()

    @classmethod
    def make(cls, spec: str, n: Optional[int] = None) -> "Curve":
        """A start curve, as `tightrope make` writes it: "torus P Q", "trefoil",
        "circle [R]", "hopf", "clasp [H]"; n vertices (per component)."""
        if n is not None and n < 1:
            raise Error(-3, f"n = {n}: a curve needs at least 3 vertices")
        err = _lib.ErrorStruct()
        h = ctypes.c_void_p()
        _check(lib.tightrope_make(spec.encode(), n or 0, ctypes.byref(h), ctypes.byref(err)), err)
        return cls._take(h)

    @classmethod
    def read(cls, path: Union[str, "os.PathLike[str]"]) -> "Curve":
        """A curve file: .vect (with plCurve constraints), .tsv, KnotPlot lists."""
        err = _lib.ErrorStruct()
        h = ctypes.c_void_p()
        _check(lib.tightrope_read(os.fsencode(path), ctypes.byref(h), ctypes.byref(err)), err)
        return cls._take(h)

    def write(self, path: Union[str, "os.PathLike[str]"], comments: Optional[str] = None) -> None:
        """Writes the curve in the format the extension names (.vect, .tsv, .txt), atomically."""
        err = _lib.ErrorStruct()
        c = comments.encode() if comments is not None else None
        _check(lib.tightrope_write(os.fsencode(path), self._h, c, ctypes.byref(err)), err)

    @property
    def vertices(self) -> int:
        return int(lib.tightrope_curve_vertices(self._h))

    @property
    def closed(self) -> List[bool]:
        return [bool(lib.tightrope_curve_closed(self._h, k)) for k in range(lib.tightrope_curve_components(self._h))]

    @property
    def constraints(self) -> int:
        """Vertices held by a constraint (a clasp's ends)."""
        return int(lib.tightrope_curve_constraints(self._h))

    @property
    def components(self) -> List[Array]:
        """Each component's vertices, (Ni, 3) copies."""
        n = self.vertices
        xyz = np.ctypeslib.as_array(lib.tightrope_curve_xyz(self._h), shape=(n, 3)).copy() if n else np.zeros((0, 3))
        k = lib.tightrope_curve_components(self._h)
        off = [int(lib.tightrope_curve_offset(self._h, i)) for i in range(k + 1)]
        return [xyz[off[i] : off[i + 1]] for i in range(k)]

    def __repr__(self) -> str:
        return f"tightrope.Curve({self.vertices} vertices in {len(self.closed)} component(s), closed {self.closed})"


class LinkLike(Protocol):
    """A spherogram/SnapPy Link, as far as tightrope uses it: its braid word."""

    def braid_word(self) -> Sequence[int]: ...


# a Link or a PD code (a list of 4-tuples of ints, an ArrayLike too) is made
# into its start curve, as make_knot/make_link make it
CurveLike = Union[Curve, LinkLike, "npt.ArrayLike", Sequence["npt.ArrayLike"]]


def _components(x: Any) -> List[Array]:
    """An (N, 3) array is one component; a list of them (or of (Ni, 3) lists) a link."""
    if isinstance(x, np.ndarray) and x.ndim == 2:
        parts = [x]
    elif isinstance(x, (list, tuple)) and x and all(isinstance(p, np.ndarray) or (isinstance(p, (list, tuple)) and p and isinstance(p[0], (list, tuple, np.ndarray))) for p in x):
        parts = list(x)
    else:
        parts = [np.asarray(x, dtype=np.float64)]
    out = []
    for k, p in enumerate(parts):
        a = np.asarray(p, dtype=np.float64)
        if a.ndim != 2 or a.shape[1] != 3:
            raise Error(-3, f"component {k}: expected an (N, 3) array of vertices, got shape {a.shape}")
        out.append(a)
    return out


def _curve(x: CurveLike) -> Curve:
    """A curve argument as the library's Curve: a Curve as it is; a
    spherogram/SnapPy Link or a PD code made into its start curve, as
    make_knot/make_link make it (_start); an (N, 3) array or a list of them
    as those coordinates. A string is refused: a name and a file path look
    alike (make_knot(name), read(path) say which is meant)."""
    if isinstance(x, Curve):
        return x
    if isinstance(x, (str, bytes, os.PathLike)):
        raise Error(-3, f"{str(x)!r} is not a curve: make_knot(name) or make_link(name) makes one by name, read(path) reads a file")
    if _is_link(x) or _is_pd(x):
        return _start(x)
    return Curve(cast("npt.ArrayLike", x))  # not a Link: the checks above


def _out(c: Curve) -> Union[Array, List[Array]]:
    comps = c.components
    return comps[0] if len(comps) == 1 else comps


def _is_link(x: Any) -> bool:
    """A spherogram/SnapPy Link (what they share: braid_word())."""
    return callable(getattr(x, "braid_word", None))


def _is_pd(x: Any) -> bool:
    """A PD code: a non-empty list of 4-tuples of integers (KnotTheory's
    convention, edges numbered from 1, or spherogram's, from 0). No curve
    looks like one: a curve's rows have 3 numbers."""
    return (
        isinstance(x, (list, tuple))
        and len(x) > 0
        and all(isinstance(c, (list, tuple)) and len(c) == 4 and all(isinstance(v, (int, np.integer)) and not isinstance(v, bool) for v in c) for c in x)
    )


def _notation(knot: Any) -> str:
    """The make spec of a knot given as a name, a PD code (a list of
    4-tuples) or a spherogram/SnapPy Link (by its braid word)."""
    if isinstance(knot, str):
        return knot
    if _is_link(knot):  # spherogram.Link, snappy.Link
        return "braid " + ",".join(str(int(g)) for g in knot.braid_word())
    if _is_pd(knot):
        # KnotTheory numbers the edges from 1, spherogram's Link.PD_code()
        # from 0: the same walk along the knot, each label one lower
        shift = 1 if min(int(v) for x in knot for v in x) == 0 else 0
        return "pd [" + ",".join("[" + ",".join(str(int(v) + shift) for v in x) + "]" for x in knot) + "]"
    raise Error(-3, f"not a knot's name, PD code or Link: {type(knot).__name__}")


def _start(knot: Any, n: Optional[int] = None) -> Curve:
    """The one way a knot or link given by name, PD code or Link becomes a
    start curve (make_knot, make_link, and measure/tighten/analyze given a
    Link or a PD code): the library's make, whose curve has as many
    components as the braid's closure or the code has; knot or link is
    that number, not a choice made here."""
    return Curve.make(_notation(knot), n)


def make_knot(name: Any, n: Optional[int] = None) -> Array:
    """A knot's start curve as an (n, 3) array: any knot to 12 crossings by
    its KnotInfo name ("7_4", "10_165", "11a_1"; its minimal diagram or
    braid closure, relaxed, the shorter; its type checked), "braid 1,-2,1,-2", "pd [[...]]", "trefoil",
    "torus P Q" (default n 200), "circle [R]" (64); or a PD code as a list
    of 4-tuples, or a spherogram/SnapPy Link (its braid word)."""
    comps = _start(name, n).components
    if len(comps) != 1:
        raise Error(-3, f"'{name}' has {len(comps)} components: make_link makes links")
    return comps[0]


def make_link(name: Any, n: Optional[int] = None) -> List[Array]:
    """A link's start curve, one (n, 3) array per component: any prime link to
    9 crossings by its LinkInfo name ("L6a4", "L2a1{1}"), "braid WORD", a
    spherogram/SnapPy Link, "hopf", "clasp [H]" (two open ropes; their end
    planes are kept only by Curve.make("clasp"))."""
    return _start(name, n).components


def read(path: Union[str, "os.PathLike[str]"]) -> Curve:
    """Reads a curve file (.vect, .tsv, KnotPlot list)."""
    return Curve.read(path)


def write(path: Union[str, "os.PathLike[str]"], curve: CurveLike, comments: Optional[str] = None) -> None:
    """Writes a curve (format by extension), atomically, exact to the last digit."""
    _curve(curve).write(path, comments)


def _num(v: float) -> Optional[float]:
    """measure --json prints a non-finite number as null."""
    return float(v) if np.isfinite(v) else None


def _fields(m: _lib.Measurement) -> Dict[str, Any]:
    d: Dict[str, Any] = {"vertices": int(m.vertices)}
    for k in ("length", "minrad", "dcsd", "thickness", "ropelength", "L_p", "L_c", "L_a"):
        d[k] = _num(getattr(m, k))
    d["minrad_vertex"] = int(m.minrad_vertex)
    if m.has_shortest_strut:
        s = m.shortest_strut
        d["shortest_strut"] = {"edges": [int(s.edges[0]), int(s.edges[1])], "positions": [float(s.positions[0]), float(s.positions[1])], "length": float(s.length)}
    return d


def _kkt(k: _lib.Kkt) -> Dict[str, Any]:
    d: Dict[str, Any] = {x: _num(getattr(k, x)) for x in ("residual", "band", "radius", "tension")}
    d.update({x: int(getattr(k, x)) for x in ("strut_rows", "strut_active", "minrad_rows", "minrad_active")})
    d.update({x: _num(getattr(k, x)) for x in ("strut_force_max", "optimality")})
    d["converged"] = bool(k.converged)
    return d


def measure(curve: CurveLike, kkt: bool = False, kkt_band: Optional[float] = None) -> Dict[str, Any]:
    """The numbers `tightrope measure --json` prints (the same keys, null as
    None): components, vertices, length, minrad, dcsd, thickness, ropelength,
    L_p, L_c, L_a, minrad_vertex, shortest_strut, per_component; with kkt=True
    the KKT certificate under "kkt" (as --kkt). A Link or a PD code is
    measured as its start curve (make_knot/make_link's)."""
    c = _curve(curve)
    err = _lib.ErrorStruct()
    m = _lib.Measurement()
    _check(lib.tightrope_measure(c._h, -1, ctypes.byref(m), ctypes.byref(err)), err)
    out: Dict[str, Any] = {"components": len(c.closed)}
    out.update(_fields(m))
    if kkt or kkt_band is not None:
        k = _lib.Kkt()
        _check(lib.tightrope_certify(c._h, kkt_band or 0.0, ctypes.byref(k), None, None, ctypes.byref(err)), err)
        out["kkt"] = _kkt(k)
    per = []
    for i, closed in enumerate(c.closed):
        _check(lib.tightrope_measure(c._h, i, ctypes.byref(m), ctypes.byref(err)), err)
        per.append({"component": i, "closed": closed, **_fields(m)})
    out["per_component"] = per
    return out


class Progress(NamedTuple):
    """What a progress callback is given while tighten runs."""

    n: int
    steps: int
    ropelength: float
    residual: float
    elapsed: float
    steps_per_s: float
    road: int
    roads: int


@dataclass
class TightenResult:
    """A tighten's outcome: .curve ((N, 3) array, a list for a link) and its summary."""

    curve: Union[Array, List[Array]]
    ropelength: float
    thickness: float
    minrad: float
    dcsd: float
    length: float
    n: int
    residual: float
    kkt_residual: Optional[float]  # None: not certified
    stopped: str  # "residual", "jammed", "target", "steps", "time-limit", "signal", "solved", "refine-failed"
    interrupted: bool
    goal_missed: bool
    elapsed: float
    steps: int
    rejected: int
    steps_per_s: float
    tries: int
    road: int
    seed: int
    rescaled: bool
    shift: Array  # a start far from the origin comes back moved by -shift (centred)
    device: str
    start_ropelength: Optional[float]  # the start's, measured before the run; None: not compared
    kkt: Optional[Dict[str, Any]] = None
    tight: Optional[Curve] = field(default=None, repr=False)  # the result as a Curve (write() keeps constraints)


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during tighten: a KeyboardInterrupt that carries the best state reached (.result)."""

    def __init__(self, result: Optional[TightenResult]) -> None:
        super().__init__("tighten interrupted; the best state is in .result")
        self.result = result


_OPTIONS = {"n", "refine_to", "residual", "target", "steps", "device", "newton", "polish", "scale", "tries", "shuffles", "seed", "kkt", "checkpoint", "progress_every"}


def tighten(curve: CurveLike, time_limit: Optional[float] = None, progress: Optional[Callable[[Progress], Any]] = None, **options: Any) -> TightenResult:
    """Tightens a curve (the command line's tighten): time_limit in seconds for
    the whole call; progress(Progress) called every progress_every seconds (0.25)
    from the run's thread; options as tighten's: n, refine_to, residual,
    target, steps, device ("reference", "auto", a spec), newton (True, False
    only on a tight start, None never), polish, scale, tries (0, default: chosen
    as the command line chooses without --tries), shuffles, seed,
    kkt (True, False, None: up to N = 2400), checkpoint (a path).
    A Link or a PD code starts from the curve make_knot/make_link make of it
    (make's default n; n= resamples it); .curve is an array for a knot, a
    list for a link.

    Ctrl-C stops the run within a step and raises tightrope.Interrupted (a
    KeyboardInterrupt) whose .result holds the best state reached."""
    bad = set(options) - _OPTIONS
    if bad:
        raise TypeError(f"tighten: unknown option(s) {', '.join(sorted(bad))}")
    c = _curve(curve)
    o = _lib.TightenOptions()
    lib.tightrope_tighten_options_init(ctypes.byref(o))
    if time_limit is not None:
        o.time_limit = float(time_limit)
    for k in ("n", "refine_to", "steps", "tries", "shuffles", "seed"):
        if k in options:
            setattr(o, k, int(options[k]))
    for k in ("residual", "target", "progress_every"):
        if k in options:
            setattr(o, k, float(options[k]))
    if "device" in options:
        o.device = str(options["device"]).encode()
    if "checkpoint" in options:
        o.checkpoint = os.fsencode(options["checkpoint"])
    if "newton" in options:
        o.newton = {True: 1, False: 0, None: -1}[options["newton"]]
    if "kkt" in options:
        o.kkt = {True: 1, False: 0, None: -1}[options["kkt"]]
    for k in ("polish", "scale"):
        if k in options:
            setattr(o, k, int(bool(options[k])))
    cancel = ctypes.c_int(0)
    o.cancel = ctypes.pointer(cancel)
    failure: List[BaseException] = []
    if progress is not None:

        def relay(p: Any, user: Any) -> None:
            q = p.contents
            try:
                progress(Progress(int(q.n), int(q.steps), q.ropelength, q.residual, q.elapsed, q.steps_per_s, q.road, q.roads))
            except BaseException as e:  # stop the run; raised once it has returned
                failure.append(e)
                cancel.value = 1

        o.progress = _lib.PROGRESS_FN(relay)
    res = _lib.TightenResultStruct()
    err = _lib.ErrorStruct()
    h = ctypes.c_void_p()
    import threading  # here, not at import: only tighten needs it

    status: List[int] = []
    done = threading.Event()

    def run() -> None:
        try:
            # SIGINT is the main thread's to take: blocked here (and in the
            # threads the library starts from here, which inherit the mask),
            # so that it never lands in the run's own system calls: Python
            # installs its handler without SA_RESTART, and a read or write
            # of the library's that a signal interrupts fails with EINTR
            if threading.current_thread() is not threading.main_thread() and hasattr(signal, "pthread_sigmask"):
                signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
            status.append(lib.tightrope_tighten(c._h, ctypes.byref(o), ctypes.byref(h), ctypes.byref(res), ctypes.byref(err)))
        finally:
            done.set()

    interrupted = False
    if threading.current_thread() is threading.main_thread():
        # the run in a thread of its own, so that Ctrl-C reaches this one
        # at once; it raises the cancel flag, the run ends at its next step.
        # An Event, not Thread.join: a join that KeyboardInterrupt breaks
        # may leave the thread looking finished (CPython gh-90882). (The
        # library keeps this process's signal handlers across PoCL's calls,
        # whose LLVM installs its own: cl_signals.h.)
        threading.Thread(target=run, name="tightrope-tighten", daemon=True).start()
        while not done.is_set():
            try:
                done.wait(0.05)
                # a SIGINT whose handler has not run: CPython before 3.12
                # recomputes the eval breaker in whichever thread holds the
                # GIL, and one that cannot handle signals (the run's, in the
                # progress callback) clears the pending signal's bit, so the
                # main thread may not look at it (python/cpython#109846);
                # PyErr_CheckSignals looks at the tripped flag itself and
                # runs the handler, and ctypes raises what it raised
                ctypes.pythonapi.PyErr_CheckSignals()
            except KeyboardInterrupt:
                interrupted = True
                cancel.value = 1
    else:
        run()
    if status[0] != 0:
        # a progress callback's exception, or Ctrl-C before the start was
        # settled (no state yet: TIGHTROPE_EINTERRUPTED), is what the caller
        # sees, not the status it caused
        if failure:
            raise failure[0]
        if interrupted and status[0] == -8:
            raise Interrupted(None)
    _check(status[0], err)
    tight = Curve._take(h)
    out = TightenResult(
        curve=_out(tight),
        ropelength=res.ropelength,
        thickness=res.thickness,
        minrad=res.minrad,
        dcsd=res.dcsd,
        length=res.length,
        n=int(res.n),
        residual=res.residual,
        kkt_residual=res.kkt_residual if res.certified else None,
        stopped=res.stopped.decode(),
        interrupted=bool(res.interrupted),
        goal_missed=bool(res.goal_missed),
        elapsed=res.elapsed,
        steps=int(res.steps),
        rejected=int(res.rejected),
        steps_per_s=res.steps_per_s,
        tries=int(res.tries),
        road=int(res.road),
        seed=int(res.seed),
        rescaled=bool(res.rescaled),
        shift=np.array(res.shift[:]),
        device=res.device.decode(errors="replace"),
        start_ropelength=None if math.isnan(res.start_ropelength) else res.start_ropelength,
        kkt=_kkt(res.kkt) if res.certified else None,
        tight=tight,
    )
    if failure:
        raise failure[0]
    if interrupted:
        raise Interrupted(out)
    return out


@dataclass
class Analysis:
    """One component's profiles as `tightrope analyze` finds them, at
    thickness 1 unless scale=False: curvature per arc of the inscribed-arc
    curve, torsion per junction between arcs, contacts (l_i, l_j, length)
    and the summary (summary.json)."""

    position: Array  # arclength of each arc (vertex) from the origin
    curvature: Array
    arc_length: Array
    junction_position: Array
    torsion: Array
    torsion_angle: Array  # signed angle between osculating planes
    accumulated_torsion: Array
    contacts: Array  # (K, 3): l_i, l_j, strut length
    summary: Dict[str, Any]


def analyze(curve: CurveLike, component: int = 0, m: Optional[int] = None, scale: bool = True, strut_tol: Optional[float] = None) -> Analysis:
    """Curvature, torsion and contacts of one component, with the summary
    (a Link or a PD code: of its start curve, as make_knot/make_link make it)."""
    import json
    c = _curve(curve)
    o = _lib.AnalyzeOptions(m or 0, 0 if scale else 1, strut_tol or 0.0)
    err = _lib.ErrorStruct()
    h = ctypes.c_void_p()
    _check(lib.tightrope_analyze(c._h, component, ctypes.byref(o), ctypes.byref(h), ctypes.byref(err)), err)
    try:

        def prof(which: int) -> Array:
            n = ctypes.c_size_t()
            p = lib.tightrope_analysis_profile(h, which, ctypes.byref(n))
            return np.ctypeslib.as_array(p, shape=(n.value,)).copy() if n.value else np.zeros(0)

        a = Analysis(
            position=prof(0),
            curvature=prof(1),
            arc_length=prof(2),
            junction_position=prof(3),
            torsion=prof(4),
            torsion_angle=prof(5),
            accumulated_torsion=prof(6),
            contacts=prof(7).reshape(-1, 3),
            summary=json.loads(lib.tightrope_analysis_summary(h).decode()),
        )
    finally:
        lib.tightrope_analysis_free(h)
    return a
