"""The ground-motion model: a horizontal ground acceleration history xg''(t) (docs/method.md, Response).

Conventions: SI units (s, m/s^2); ``accel`` is positive toward +x (to the right), the same x as
the arch geometry.  A time may appear twice in a row to encode a step (the idealised pulses;
records have strictly increasing times, :func:`.records.check_time_order`); the history is
right-continuous there.  Before t = 0 and after the last sample the acceleration is 0.
"""

from __future__ import annotations

import bisect
import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import ArchInputError
from ..units import G

__all__ = ["UNITS", "GroundMotion", "from_samples", "MAX_PGA_G", "WARN_PGA_G",
           "MAX_RECORD_DT_S", "WARN_RECORD_DT_S", "check_pga"]


#: Accepted acceleration units and their factor to m/s^2.
UNITS = {"g": G, "m/s2": 1.0, "cm/s2": 0.01}

# A query time this close to a step time counts as the step time, so that e.g. t = 0.6 is "at"
# the step 3 * 0.2 = 0.6000000000000001 of Oppenheim's pulse (relative to max(1 s, duration)).
_STEP_SNAP_REL = 1e-12


# Plausibility of a ground motion. Thresholds in one place; the readers, the pulses and the
# studies that scale motions refuse what cannot be meant and warn about the suspicious.

#: Largest ground acceleration accepted [g]. The strongest horizontal PGAs ever recorded are
#: about 3-4 g; 20 g is no earthquake but a mistake (a record in cm/s^2 read as g gives
#: hundreds of g, a stray --scale 1e6 millions), and far beyond it the fixed-step rocking
#: kernel breaks down (division by zero near 1e6 g).
MAX_PGA_G = 20.0
#: Above this PGA [g] a warning: beyond the strongest records, so probably a units or scale
#: slip, though a deliberate stress test is possible.
WARN_PGA_G = 3.0
#: Largest sampling interval [s] of a sampled record. Strong-motion records are sampled at
#: 0.005-0.02 s; at 0.1 s (10 Hz) the pulses that rock an arch (0.1-1 s) are not resolved, and
#: a larger step usually means times in the wrong unit (ms, samples) or a decimated file.
MAX_RECORD_DT_S = 0.1
#: Above this interval [s] a warning: coarser than any strong-motion archive distributes.
WARN_RECORD_DT_S = 0.05


def check_pga(pga_g: float, what: str, cause: str, warn: bool = True) -> None:
    """Refuse a PGA above :data:`MAX_PGA_G` (ArchInputError naming ``what``, the value and the
    likely ``cause``) and warn above :data:`WARN_PGA_G` (with ``warn``)."""
    if not pga_g <= MAX_PGA_G:
        raise ArchInputError(f"{what}: PGA {pga_g:.4g} g; allowed at most {MAX_PGA_G:g} g "
                             f"({cause})")
    if warn and pga_g > WARN_PGA_G:
        warnings.warn(f"{what}: PGA {pga_g:.4g} g is above the strongest records "
                      f"(about {WARN_PGA_G:g} g); {cause}", stacklevel=3)


# --------------------------------------------------------------------------------------------
# validation helpers
# --------------------------------------------------------------------------------------------


def _real(field: str, value, unit: str = "") -> float:
    """``value`` as a finite float, or ArchInputError naming ``field``."""
    if isinstance(value, (bool, np.bool_)):
        raise ArchInputError(f"{field}: {value!r}; allowed a finite number{_u(unit)}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ArchInputError(f"{field}: {value!r}; allowed a finite number{_u(unit)}") from None
    if not math.isfinite(x):
        raise ArchInputError(f"{field}: {x}{_u(unit)}; allowed a finite number{_u(unit)}")
    return x


def _positive(field: str, value, unit: str = "s") -> float:
    x = _real(field, value, unit)
    if x <= 0.0:
        raise ArchInputError(f"{field}: {x:g}{_u(unit)}; allowed > 0{_u(unit)}")
    return x


def _count(field: str, value, minimum: int) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise ArchInputError(f"{field}: {value!r}; allowed an integer >= {minimum}")
    if value < minimum:
        raise ArchInputError(f"{field}: {value}; allowed an integer >= {minimum}")
    return int(value)


def _u(unit: str) -> str:
    return f" {unit}" if unit else ""


def _unit_factor(units) -> float:
    if not isinstance(units, str) or units not in UNITS:
        allowed = ", ".join(repr(k) for k in UNITS)
        raise ArchInputError(f"units: {units!r}; allowed one of {allowed}")
    return UNITS[units]


# --------------------------------------------------------------------------------------------
# the model
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """Horizontal ground acceleration xg''(t), piecewise linear through samples.

    ``times`` [s]: non-decreasing, starting at 0.0; one time may appear twice in a row to encode
    a step.  ``accel`` [m/s^2]: positive toward +x (to the right).  Both arrays are copied and
    made read-only.  After ``times[-1]`` the acceleration is 0 (a nonzero last sample drops to 0
    at the end); before 0 it is 0 too.
    """

    times: np.ndarray
    accel: np.ndarray
    name: str = "ground motion"
    source: str = ""

    def __post_init__(self):
        t = self._array("ground motion times", self.times, "s")
        a = self._array("ground motion accel", self.accel, "m/s^2")
        if t.size != a.size:
            raise ArchInputError(
                f"ground motion times: {t.size} samples but accel has {a.size}; "
                "allowed equal lengths"
            )
        if t.size < 2:
            raise ArchInputError(f"ground motion times: {t.size} sample(s); allowed >= 2 samples")
        if t[0] != 0.0:
            raise ArchInputError(f"ground motion times: first time {t[0]:g} s; allowed 0 s")
        dt = np.diff(t)
        bad = np.flatnonzero(dt < 0.0)
        if bad.size:
            i = int(bad[0]) + 1
            raise ArchInputError(
                f"ground motion times: {t[i]:g} s at index {i} follows {t[i - 1]:g} s; "
                "allowed non-decreasing times"
            )
        # Three equal times in a row would make the value at that time ambiguous.
        triple = np.flatnonzero((dt[:-1] == 0.0) & (dt[1:] == 0.0))
        if triple.size:
            i = int(triple[0])
            raise ArchInputError(
                f"ground motion times: {t[i]:g} s repeated 3+ times from index {i}; "
                "allowed at most 2 equal times in a row (one step)"
            )
        if not isinstance(self.name, str):
            raise ArchInputError(f"ground motion name: {self.name!r}; allowed a string")
        if not isinstance(self.source, str):
            raise ArchInputError(f"ground motion source: {self.source!r}; allowed a string")
        t.setflags(write=False)
        a.setflags(write=False)
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "accel", a)
        # Step times (repeated times), used to snap query times that miss a step by rounding.
        steps = t[1:][dt == 0.0]
        steps.setflags(write=False)
        object.__setattr__(self, "_steps", steps)
        object.__setattr__(self, "_snap", _STEP_SNAP_REL * max(1.0, float(t[-1])))
        # Python lists for the scalar fast path (an ODE right-hand side calls with floats).
        object.__setattr__(self, "_tl", t.tolist())
        object.__setattr__(self, "_al", a.tolist())

    @staticmethod
    def _array(field: str, values, unit: str) -> np.ndarray:
        try:
            arr = np.array(values, dtype=float)  # a copy: the caller's array stays writable
        except (TypeError, ValueError):
            raise ArchInputError(f"{field}: not a list of numbers; allowed finite numbers in {unit}") from None
        if arr.ndim != 1:
            raise ArchInputError(f"{field}: shape {arr.shape}; allowed a 1-d sequence")
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            i = int(bad[0])
            raise ArchInputError(f"{field}: {arr[i]} at index {i}; allowed finite numbers in {unit}")
        return arr

    def __repr__(self) -> str:
        return (
            f"GroundMotion(name={self.name!r}, samples={self.times.size}, "
            f"duration={self.duration:g} s, pga={self.pga_g:.4g} g)"
        )

    # ---- evaluation --------------------------------------------------------------------------

    def __call__(self, t):
        """xg''(t) [m/s^2] at time(s) ``t`` [s]: a float for a scalar, an array for an array.

        Linear between samples, right-continuous at steps, 0 for t < 0 and t > duration.
        """
        if isinstance(t, (float, int)) and not isinstance(t, bool):
            return self._scalar(float(t))
        try:
            tt = np.asarray(t, dtype=float)
        except (TypeError, ValueError):
            raise ArchInputError(f"time: {t!r}; allowed real numbers in s") from None
        if tt.ndim == 0:
            return self._scalar(float(tt))
        return self._vector(tt)

    def _snap_scalar(self, x: float) -> float:
        steps = self._steps
        if steps.size:
            k = bisect.bisect_left(self._tl, x)
            # only step times can be "missed"; look at the nearest few sample times
            for j in (k - 1, k):
                if 0 <= j < len(self._tl):
                    s = self._tl[j]
                    if s != x and abs(s - x) <= self._snap and self._is_step(j):
                        return s
        return x

    def _is_step(self, j: int) -> bool:
        tl = self._tl
        return (j > 0 and tl[j - 1] == tl[j]) or (j + 1 < len(tl) and tl[j + 1] == tl[j])

    def _scalar(self, x: float) -> float:
        if math.isnan(x):
            raise ArchInputError("time: nan; allowed real numbers in s")
        x = self._snap_scalar(x)
        tl, al = self._tl, self._al
        if x < 0.0 or x > tl[-1]:
            return 0.0
        i = bisect.bisect_right(tl, x)  # tl[i-1] <= x < tl[i]; later value at a repeated time
        if i == len(tl):
            return al[-1]  # x == duration
        t0, t1 = tl[i - 1], tl[i]
        return al[i - 1] + (al[i] - al[i - 1]) * (x - t0) / (t1 - t0)

    def _vector(self, tt: np.ndarray) -> np.ndarray:
        if np.isnan(tt).any():
            raise ArchInputError("time: nan; allowed real numbers in s")
        t, a = self.times, self.accel
        steps = self._steps
        if steps.size:
            k = np.clip(np.searchsorted(steps, tt), 1, steps.size) - 1
            for cand in (steps[k], steps[np.minimum(k + 1, steps.size - 1)]):
                tt = np.where(np.abs(cand - tt) <= self._snap, cand, tt)
        n = t.size
        i = np.searchsorted(t, tt, side="right")
        inside = (tt >= 0.0) & (i < n)
        out = np.zeros(tt.shape, dtype=float)
        ii = i[inside]
        x = tt[inside]
        t0, t1 = t[ii - 1], t[ii]
        a0, a1 = a[ii - 1], a[ii]
        out[inside] = a0 + (a1 - a0) * (x - t0) / (t1 - t0)
        out[tt == t[-1]] = a[-1]
        return out

    # ---- properties and derived motions -----------------------------------------------------

    @property
    def duration(self) -> float:
        """Time of the last sample [s]; the acceleration is 0 afterwards."""
        return float(self.times[-1])

    @property
    def pga(self) -> float:
        """Peak ground acceleration max |accel| [m/s^2]."""
        return float(np.max(np.abs(self.accel)))

    @property
    def pga_g(self) -> float:
        """Peak ground acceleration in g."""
        return self.pga / G

    def scaled(self, factor) -> GroundMotion:
        """Same times, ``accel * factor`` (finite, may be negative or 0)."""
        f = _real("scale factor", factor)
        src = f"{self.source}; scaled by {f:g}" if self.source else f"scaled by {f:g}"
        return GroundMotion(self.times, self.accel * f, self.name, src)

    def mirrored(self) -> GroundMotion:
        """The motion mirrored left-right: ``accel * -1`` (M_l and M_r swap roles)."""
        src = f"{self.source}; mirrored" if self.source else "mirrored"
        return GroundMotion(self.times, -self.accel, self.name, src)

    def breakpoints(self) -> np.ndarray:
        """Distinct sample times [s], increasing: where xg'' has a kink or a step.

        An integrator should stop at these so that it never steps across a discontinuity.
        """
        return np.unique(self.times)


def from_samples(accel, dt: float, units: str = "g", name: str = "ground motion") -> GroundMotion:
    """Uniformly sampled record: accel[k] at t = k dt [s], converted from ``units`` to m/s^2."""
    factor = _unit_factor(units)
    step = _positive("dt", dt)
    try:
        arr = np.array(accel, dtype=float)
    except (TypeError, ValueError):
        raise ArchInputError("accel: not a list of numbers; allowed finite numbers") from None
    if arr.ndim != 1:
        raise ArchInputError(f"accel: shape {arr.shape}; allowed a 1-d sequence")
    if arr.size < 2:
        raise ArchInputError(f"accel: {arr.size} sample(s); allowed >= 2 samples")
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        i = int(bad[0])
        raise ArchInputError(f"accel: {arr[i]} at index {i}; allowed finite numbers")
    t = np.arange(arr.size) * step  # k * dt: no accumulated rounding
    return GroundMotion(t, arr * factor, name, f"samples: dt = {step:g} s, units {units}")
