"""The C library (include/tightrope/tightrope.h) through ctypes: its structs
and prototypes, and where the library is found."""

from __future__ import annotations

import ctypes
import os
from typing import Any, Optional

c_size_t = ctypes.c_size_t
c_double = ctypes.c_double
c_int = ctypes.c_int
c_long = ctypes.c_long
c_char_p = ctypes.c_char_p
c_void_p = ctypes.c_void_p
POINTER = ctypes.POINTER


class ErrorStruct(ctypes.Structure):
    _fields_ = [("status", c_int), ("message", ctypes.c_char * 1024)]


class Strut(ctypes.Structure):
    _fields_ = [("edges", c_size_t * 2), ("positions", c_double * 2), ("length", c_double)]


class Measurement(ctypes.Structure):
    _fields_ = [
        ("vertices", c_size_t),
        ("length", c_double),
        ("minrad", c_double),
        ("dcsd", c_double),
        ("thickness", c_double),
        ("ropelength", c_double),
        ("L_p", c_double),
        ("L_c", c_double),
        ("L_a", c_double),
        ("minrad_vertex", c_size_t),
        ("has_shortest_strut", c_int),
        ("shortest_strut", Strut),
    ]


class Kkt(ctypes.Structure):
    _fields_ = [
        ("residual", c_double),
        ("band", c_double),
        ("radius", c_double),
        ("tension", c_double),
        ("strut_rows", c_size_t),
        ("strut_active", c_size_t),
        ("minrad_rows", c_size_t),
        ("minrad_active", c_size_t),
        ("strut_force_max", c_double),
        ("optimality", c_double),
        ("converged", c_int),
    ]


class ProgressStruct(ctypes.Structure):
    _fields_ = [
        ("n", c_size_t),
        ("steps", c_long),
        ("ropelength", c_double),
        ("residual", c_double),
        ("elapsed", c_double),
        ("steps_per_s", c_double),
        ("road", c_int),
        ("roads", c_int),
    ]


PROGRESS_FN = ctypes.CFUNCTYPE(None, POINTER(ProgressStruct), c_void_p)


class TightenOptions(ctypes.Structure):
    _fields_ = [
        ("time_limit", c_double),
        ("n", c_long),
        ("refine_to", c_long),
        ("residual", c_double),
        ("target", c_double),
        ("steps", c_long),
        ("device", c_char_p),
        ("newton", c_int),
        ("polish", c_int),
        ("scale", c_int),
        ("tries", c_long),
        ("shuffles", c_long),
        ("seed", c_long),
        ("kkt", c_int),
        ("checkpoint", c_char_p),
        ("progress", PROGRESS_FN),
        ("progress_every", c_double),
        ("user", c_void_p),
        ("cancel", POINTER(c_int)),  # volatile sig_atomic_t *: an int on every Linux
    ]


class TightenResultStruct(ctypes.Structure):
    _fields_ = [
        ("n", c_size_t),
        ("ropelength", c_double),
        ("thickness", c_double),
        ("minrad", c_double),
        ("dcsd", c_double),
        ("length", c_double),
        ("residual", c_double),
        ("kkt_residual", c_double),
        ("certified", c_int),
        ("kkt", Kkt),
        ("stopped", ctypes.c_char * 32),
        ("interrupted", c_int),
        ("goal_missed", c_int),
        ("elapsed", c_double),
        ("steps", c_long),
        ("rejected", c_long),
        ("steps_per_s", c_double),
        ("tries", c_long),
        ("road", c_long),
        ("seed", c_long),
        ("rescaled", c_int),
        ("shift", c_double * 3),
        ("device", ctypes.c_char * 128),
        ("start_ropelength", c_double),
    ]


class AnalyzeOptions(ctypes.Structure):
    _fields_ = [("m", c_size_t), ("no_scale", c_int), ("strut_tol", c_double)]


def _find() -> str:
    """TIGHTROPE_LIBRARY (a path), else the copy inside the package (a wheel
    built by pip install ./python), else the system's (an installed
    libtightrope.so)."""
    env = os.environ.get("TIGHTROPE_LIBRARY")
    if env:
        if os.sep in env and not os.path.exists(env):  # (a bare name is dlopen's to search)
            raise ImportError(f"tightrope: TIGHTROPE_LIBRARY={env}: no such file")
        return env
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "libtightrope.so")
    if os.path.exists(here):
        return here
    import ctypes.util  # (slow: only when the package holds no library)

    found = ctypes.util.find_library("tightrope")
    if found:
        return found
    raise ImportError(
        "tightrope: libtightrope.so not found (install the package with pip install ./python, "
        "or set TIGHTROPE_LIBRARY to the library's path)"
    )


_SIGNATURES = {
    "tightrope_version": (c_char_p, []),
    "tightrope_strerror": (c_char_p, [c_int]),
    "tightrope_curve_new": (c_int, [c_int, POINTER(c_size_t), POINTER(c_int), POINTER(c_double), POINTER(c_void_p), POINTER(ErrorStruct)]),
    "tightrope_curve_free": (None, [c_void_p]),
    "tightrope_curve_vertices": (c_size_t, [c_void_p]),
    "tightrope_curve_components": (c_int, [c_void_p]),
    "tightrope_curve_offset": (c_size_t, [c_void_p, c_int]),
    "tightrope_curve_closed": (c_int, [c_void_p, c_int]),
    "tightrope_curve_constraints": (c_int, [c_void_p]),
    "tightrope_curve_xyz": (POINTER(c_double), [c_void_p]),
    "tightrope_make": (c_int, [c_char_p, c_size_t, POINTER(c_void_p), POINTER(ErrorStruct)]),
    "tightrope_read": (c_int, [c_char_p, POINTER(c_void_p), POINTER(ErrorStruct)]),
    "tightrope_write": (c_int, [c_char_p, c_void_p, c_char_p, POINTER(ErrorStruct)]),
    "tightrope_measure": (c_int, [c_void_p, c_int, POINTER(Measurement), POINTER(ErrorStruct)]),
    "tightrope_certify": (c_int, [c_void_p, c_double, POINTER(Kkt), POINTER(c_double), POINTER(c_double), POINTER(ErrorStruct)]),
    "tightrope_tighten_options_init": (None, [POINTER(TightenOptions)]),
    "tightrope_tighten": (c_int, [c_void_p, POINTER(TightenOptions), POINTER(c_void_p), POINTER(TightenResultStruct), POINTER(ErrorStruct)]),
    "tightrope_analyze": (c_int, [c_void_p, c_int, POINTER(AnalyzeOptions), POINTER(c_void_p), POINTER(ErrorStruct)]),
    "tightrope_analysis_free": (None, [c_void_p]),
    "tightrope_analysis_profile": (POINTER(c_double), [c_void_p, c_int, POINTER(c_size_t)]),
    "tightrope_analysis_summary": (c_char_p, [c_void_p]),
}


class Library:
    """libtightrope, opened on first use: `import tightrope` finds the file
    (a missing library is an ImportError there) but leaves the dlopen --
    the library and what it links (CHOLMOD, BLAS, LAPACK, OpenCL's loader),
    about as long again as the rest of the package's import -- to the first
    call that needs it (docs/python.md). Each function, once looked up, is
    kept as an attribute, so later calls do not come back here."""

    def __init__(self, path: str) -> None:
        self._path = path
        self._cdll: Optional[ctypes.CDLL] = None

    def _open(self) -> ctypes.CDLL:
        if self._cdll is None:  # two threads may both open it: dlopen counts, the handle is the same
            try:
                cdll = ctypes.CDLL(self._path)  # CDLL: the GIL is released during each call
            except OSError as e:
                raise OSError(f"tightrope: cannot load {self._path}: {e}") from e
            for name, (res, args) in _SIGNATURES.items():
                f = getattr(cdll, name)
                f.restype = res
                f.argtypes = args
            self._cdll = cdll
        return self._cdll

    def __getattr__(self, name: str) -> Any:
        if not name.startswith("tightrope_"):  # (copy, pickle: not the library's)
            raise AttributeError(name)
        f = getattr(self._open(), name)
        setattr(self, name, f)
        return f


lib = Library(_find())
