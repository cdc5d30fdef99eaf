"""The app's request fields, checked as the command line checks its flags: a number, a choice,
an object, the request itself; the bound on voussoirs and the one lock of library calls
shared by the endpoints; and the rounding of coordinates in the JSON it answers.

Each raises :class:`~archrock.errors.ArchInputError` naming the field; the server turns it into
HTTP 400.
"""

from __future__ import annotations

import math
import threading

import numpy as np

from ..errors import ArchInputError

__all__ = ["number", "choice", "object_field", "request_object", "only", "friction", "xy",
           "MAX_VOUSSOIRS", "COMPUTE_LOCK", "ARCH_FIELDS"]

#: The fields of an arch (the JSON form of the CLI's geometry options).
ARCH_FIELDS = ("shape", "span", "rise", "thickness", "thickness_crown", "joints", "voussoirs",
               "density", "radius", "embrace", "defects", "pier_height", "pier_width",
               "pier_courses", "geometry", "name", "fc")

#: Most voussoirs of an arch the page may ask for (the CLI allows more; an interactive page
#: should answer in about a second).
MAX_VOUSSOIRS = 120

#: Library calls are made one at a time within a process: numba's parallel loops must not
#: run in two threads at once.  The jobs (ensemble, curve, report) run in the job worker
#: process (app/jobs.py), so the server's statics never wait on a job's lock.
COMPUTE_LOCK = threading.RLock()


def number(params: dict, name: str, default=None, *, integer: bool = False):
    """``params[name]`` as a finite float (or int), ``default`` when absent or null;
    ArchInputError naming ``name`` otherwise."""
    v = params.get(name, default)
    if v is None:
        return None
    if isinstance(v, str):
        try:
            v = float(v.strip())
        except ValueError:
            raise ArchInputError(f"{name}: expected a number, got {v!r}") from None
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ArchInputError(f"{name}: expected a number, got {v!r}")
    if not math.isfinite(v):
        raise ArchInputError(f"{name}: must be a finite number, got {v!r}")
    if integer:
        if int(v) != v:
            raise ArchInputError(f"{name}: expected an integer, got {v!r}")
        return int(v)
    return float(v)


def choice(params: dict, name: str, allowed, default=None):
    v = params.get(name, default)
    if v is None:
        return None
    if v not in allowed:
        raise ArchInputError(f"{name}: {v!r}; allowed one of {', '.join(allowed)}")
    return v


def object_field(params, name: str) -> dict:
    v = params.get(name) if isinstance(params, dict) else None
    if v is None:
        return {}
    if not isinstance(v, dict):
        raise ArchInputError(f"{name}: expected an object, got {type(v).__name__}")
    return v


def request_object(body) -> dict:
    if not isinstance(body, dict):
        raise ArchInputError(f"request: expected a JSON object, got {type(body).__name__}")
    return body


def only(params: dict, allowed, where: str | None = None) -> dict:
    """``params`` when every key is in ``allowed``; else ArchInputError naming the first unknown
    key (``where.key`` inside the object ``where``) and the allowed ones: a misspelt or
    misplaced field is refused, never ignored (``{"thickness": -3}`` beside ``"arch"`` would
    otherwise answer for the default thickness)."""
    for key in params:
        if key not in allowed:
            name = f"{where}.{key}" if where else str(key)
            hint = (f" ({key} is a field of the arch: put it inside \"arch\")"
                    if where is None and key in ARCH_FIELDS and "arch" in allowed else "")
            raise ArchInputError(f"unknown field {name[:60]!r}; allowed"
                                 f"{' in ' + where if where else ''}: "
                                 f"{', '.join(allowed)}{hint}")
    return params


def friction(params: dict, default):
    """The Coulomb friction coefficient of ``params["friction"]``: a finite number > 0,
    ``default`` when absent, None for "none" (sliding excluded by the user, Heyman's
    hypothesis)."""
    v = params.get("friction")
    if isinstance(v, str) and v.strip().lower() == "none":
        return None
    mu = number(params, "friction", default)
    if mu is not None and mu <= 0:
        raise ArchInputError(f"friction: {mu:g}; allowed a finite number > 0, or none "
                             f"(sliding excluded)")
    return mu


def xy(a) -> list:
    """Points as JSON lists [m], rounded to the micrometre."""
    return np.round(np.asarray(a, float), 6).tolist()
