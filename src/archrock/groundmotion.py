"""Ground motions: horizontal ground acceleration histories xg''(t) (METHOD section 3).

Conventions: SI units (s, m/s^2); ``accel`` is positive toward +x (to the right), the same x as
the arch geometry.  Amplitudes passed to the pulse constructors are in g (multiples of ``G``) and
may be negative: the paper's forcing is Oppenheim's pulse with a = -1 g, t_p = 0.20 s.

A :class:`GroundMotion` is a piecewise-linear history through its samples.  A time may appear
twice in a row to encode a step (a jump in acceleration); the history is right-continuous there
(at the repeated time the later value applies).  Before t = 0 and after the last sample the
acceleration is 0.  So a record whose last sample is nonzero drops to 0 just after its end; the
pulse constructors end their histories with an explicit 0 where the drop matters.

The module has two parts: the pure numpy model and constructors, then the file readers
(two-column text files and PEER NGA ``.AT2`` files).  Every bad input raises
:class:`archrock.errors.ArchInputError` with a one-line message naming the field.
"""

from __future__ import annotations

import bisect
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import ArchInputError
from .units import G  # re-exported: the package's gravity constant [m/s^2]

__all__ = [
    "G",
    "UNITS",
    "PULSE_KINDS",
    "GroundMotion",
    "oppenheim_pulse",
    "rectangular_pulse",
    "half_sine_pulse",
    "one_sine_pulse",
    "ricker_pulse",
    "pulse",
    "pulse_kind",
    "from_samples",
    "read_two_column",
    "read_at2",
    "load_record",
]


#: Accepted acceleration units and their factor to m/s^2.
UNITS = {"g": G, "m/s2": 1.0, "cm/s2": 0.01}

#: Pulse kinds accepted by :func:`pulse`.
PULSE_KINDS = ("oppenheim", "rectangular", "half-sine", "one-sine", "ricker")

# A query time this close to a step time counts as the step time, so that e.g. t = 0.6 is "at"
# the step 3 * 0.2 = 0.6000000000000001 of Oppenheim's pulse (relative to max(1 s, duration)).
_STEP_SNAP_REL = 1e-12

_MIN_SAMPLES = 4  # smallest number of intervals for the sampled pulses


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


def _short(text: str, limit: int = 60) -> str:
    """repr of a text snippet for a one-line message (repr escapes newlines)."""
    text = text.strip()
    if len(text) > limit:
        text = text[:limit] + "..."
    return repr(text)


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


# --------------------------------------------------------------------------------------------
# constructors
# --------------------------------------------------------------------------------------------


def oppenheim_pulse(amplitude_g: float = -1.0, duration: float = 0.2) -> GroundMotion:
    """Oppenheim's idealised pulse (the paper's forcing, a = -1 g, t_p = 0.2 s).

    xg'' = a on [0, t_p), -a/2 on [t_p, 3 t_p), 0 from 3 t_p on; encoded exactly with steps:
    times [0, t_p, t_p, 3 t_p, 3 t_p], accel [a, a, -a/2, -a/2, 0].  Zero net velocity change.
    """
    ag = _real("pulse amplitude", amplitude_g, "g")
    a = ag * G
    tp = _positive("pulse duration", duration)
    t = [0.0, tp, tp, 3.0 * tp, 3.0 * tp]
    acc = [a, a, -0.5 * a, -0.5 * a, 0.0]
    return GroundMotion(
        np.array(t), np.array(acc), "Oppenheim pulse",
        f"oppenheim pulse: a = {ag:g} g, t_p = {tp:g} s",
    )


def rectangular_pulse(amplitude_g: float, duration: float) -> GroundMotion:
    """xg'' = a on [0, t_p), 0 from t_p on (times [0, t_p, t_p], accel [a, a, 0])."""
    ag = _real("pulse amplitude", amplitude_g, "g")
    a = ag * G
    tp = _positive("pulse duration", duration)
    return GroundMotion(
        np.array([0.0, tp, tp]), np.array([a, a, 0.0]), "rectangular pulse",
        f"rectangular pulse: a = {ag:g} g, t_p = {tp:g} s",
    )


def half_sine_pulse(amplitude_g: float, duration: float, samples_per_pulse: int = 200) -> GroundMotion:
    """xg'' = a sin(pi t / t_p) on [0, t_p], 0 after; ``samples_per_pulse`` intervals.

    Velocity change 2 a t_p / pi.
    """
    ag = _real("pulse amplitude", amplitude_g, "g")
    a = ag * G
    tp = _positive("pulse duration", duration)
    n = _count("samples per pulse", samples_per_pulse, _MIN_SAMPLES)
    t = np.linspace(0.0, tp, n + 1)
    acc = a * np.sin(np.pi * t / tp)
    acc[0] = acc[-1] = 0.0  # exact zeros instead of a * sin(pi) ~ 1e-16 a
    return GroundMotion(t, acc, "half-sine pulse", f"half-sine pulse: a = {ag:g} g, t_p = {tp:g} s")


def one_sine_pulse(amplitude_g: float, duration: float, samples_per_pulse: int = 400) -> GroundMotion:
    """xg'' = a sin(2 pi t / t_p) on [0, t_p] (one full cycle), 0 after.

    Zero net velocity change; ``samples_per_pulse`` intervals.
    """
    ag = _real("pulse amplitude", amplitude_g, "g")
    a = ag * G
    tp = _positive("pulse duration", duration)
    n = _count("samples per pulse", samples_per_pulse, _MIN_SAMPLES)
    t = np.linspace(0.0, tp, n + 1)
    acc = a * np.sin(2.0 * np.pi * t / tp)
    acc[0] = acc[-1] = 0.0
    if n % 2 == 0:
        acc[n // 2] = 0.0
    return GroundMotion(t, acc, "one-sine pulse", f"one-sine pulse: a = {ag:g} g, t_p = {tp:g} s")


def ricker_pulse(amplitude_g: float, period: float, samples: int = 600) -> GroundMotion:
    """Ricker wavelet a (1 - 2 u^2) exp(-u^2), u = pi f (t - t0), f = 1/period.

    Peak a at its centre t0 = 1.5 * period, side lobes -0.446 a.  With this t0 the wavelet is
    below 1e-8 |a| at t = 0 and t = 2 t0, so it starts and ends (set exactly to 0 there) without
    a noticeable jump.  Sampled with ``samples`` intervals (even, so t0 is a sample) on [0, 2 t0].
    """
    ag = _real("pulse amplitude", amplitude_g, "g")
    a = ag * G
    T = _positive("pulse period", period)
    n = _count("samples", samples, _MIN_SAMPLES)
    if n % 2:
        raise ArchInputError(f"samples: {n}; allowed an even integer >= {_MIN_SAMPLES} (so the peak is sampled)")
    t0 = 1.5 * T
    t = np.linspace(0.0, 2.0 * t0, n + 1)
    t[n // 2] = t0  # exact centre, so the peak value is exactly a
    u2 = (np.pi * (t - t0) / T) ** 2
    acc = a * (1.0 - 2.0 * u2) * np.exp(-u2)
    acc[0] = acc[-1] = 0.0
    return GroundMotion(t, acc, "Ricker pulse", f"ricker pulse: a = {ag:g} g, period = {T:g} s, t0 = {t0:g} s")


_PULSES = {
    "oppenheim": oppenheim_pulse,
    "rectangular": rectangular_pulse,
    "half-sine": half_sine_pulse,
    "one-sine": one_sine_pulse,
    "ricker": ricker_pulse,
}


def pulse(kind: str, amplitude_g: float, duration: float) -> GroundMotion:
    """Pulse by name: kind in PULSE_KINDS ('_' and case are tolerated); for 'ricker' the
    duration is the period.  Default sampling of each constructor."""
    return _PULSES[pulse_kind(kind)](amplitude_g, duration)


def pulse_kind(kind: str) -> str:
    """The canonical name of a pulse kind ('_' and case tolerated), or a clear error."""
    key = kind.strip().lower().replace("_", "-") if isinstance(kind, str) else None
    if key not in PULSE_KINDS:
        raise ArchInputError(f"pulse kind: {kind!r}; allowed one of {', '.join(PULSE_KINDS)}")
    return key


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


# --------------------------------------------------------------------------------------------
# file readers
# --------------------------------------------------------------------------------------------


def _read_lines(path) -> tuple[Path, list[str]]:
    if not isinstance(path, (str, Path)) and not hasattr(path, "__fspath__"):
        raise ArchInputError(f"record path: {path!r}; allowed a file path")
    p = Path(path)
    if not p.is_file():
        what = "is not a file" if p.exists() else "file not found"
        raise ArchInputError(f"record {p}: {what}; allowed an existing readable file")
    try:
        text = p.read_text(encoding="utf-8", errors="strict")
    except UnicodeDecodeError:
        try:
            text = p.read_text(encoding="latin-1")  # old headers may hold accented site names
        except OSError as exc:
            raise ArchInputError(f"record {p}: cannot read ({exc.strerror}); allowed a readable file") from None
    except OSError as exc:
        raise ArchInputError(f"record {p}: cannot read ({exc.strerror}); allowed a readable file") from None
    if "\x00" in text:
        raise ArchInputError(f"record {p}: binary data; allowed a text file")
    return p, text.splitlines()  # splitlines handles the CRLF endings of PEER files


def _number(p: Path, lineno: int, token: str) -> float:
    try:
        x = float(token)
    except ValueError:
        raise ArchInputError(f"record {p.name}: line {lineno}: {_short(token)} is not a number") from None
    if not math.isfinite(x):
        raise ArchInputError(f"record {p.name}: line {lineno}: {token!r} is not finite; allowed finite numbers")
    return x


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def read_two_column(path, units: str = "g", name: str | None = None) -> GroundMotion:
    """Read "time accel" rows (whitespace- or comma-separated) into a GroundMotion.

    '#' starts a comment (whole line or trailing); blank lines are skipped; the first non-comment
    line may be a non-numeric header.  Times [s] must be >= 0 and increasing; one time may appear
    twice in a row (a step).  If the first time is > 0, a zero sample (0, 0) is prepended, so the
    record ramps from 0 to its first value.  ``units`` in UNITS, converted to m/s^2.
    """
    factor = _unit_factor(units)
    p, lines = _read_lines(path)
    ts: list[float] = []
    acs: list[float] = []
    linenos: list[int] = []
    seen_first = False
    for lineno, raw in enumerate(lines, start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        tokens = line.replace(",", " ").replace(";", " ").split()
        if not seen_first:
            seen_first = True
            if not any(_is_number(tok) for tok in tokens):
                continue  # a header line such as "time, accel" (a line with a number is data)
        if len(tokens) != 2:
            raise ArchInputError(
                f"record {p.name}: line {lineno}: {len(tokens)} columns; allowed 2 (time accel)"
            )
        t = _number(p, lineno, tokens[0])
        a = _number(p, lineno, tokens[1])
        if not ts and t < 0.0:
            raise ArchInputError(f"record {p.name}: line {lineno}: time {t:g} s; allowed >= 0 s")
        if ts and t < ts[-1]:
            raise ArchInputError(
                f"record {p.name}: line {lineno}: time {t:g} s after {ts[-1]:g} s; allowed increasing times"
            )
        if len(ts) >= 2 and t == ts[-1] == ts[-2]:
            raise ArchInputError(
                f"record {p.name}: line {lineno}: time {t:g} s a third time; allowed at most 2 equal times (a step)"
            )
        ts.append(t)
        acs.append(a)
        linenos.append(lineno)
    if not ts:
        raise ArchInputError(f"record {p.name}: empty record (no 'time accel' rows); allowed >= 2 samples")
    if ts[0] > 0.0:
        ts.insert(0, 0.0)
        acs.insert(0, 0.0)
    if len(ts) < 2:
        raise ArchInputError(f"record {p.name}: 1 sample; allowed >= 2 samples")
    return GroundMotion(
        np.array(ts), np.array(acs) * factor, name if name is not None else p.stem,
        f"{p} (two-column, {units})",
    )


_NGA_HEADER = re.compile(r"NPTS\s*=\s*(\S+?)\s*,?\s*DT\s*=\s*(\S+?)\s*,?\s*(SEC\b.*)?$", re.IGNORECASE)
_OLD_HEADER = re.compile(r"^\s*(\S+)\s+(\S+)\s+NPTS\s*,?\s*DT\b", re.IGNORECASE)


def read_at2(path) -> GroundMotion:
    """Read a PEER NGA ``.AT2`` acceleration file (values in g) into a GroundMotion [m/s^2].

    Four header lines; the 4th is ``NPTS=  5000, DT=   .0100 SEC,`` (NGA-West2; commas and case
    optional) or ``  4000    0.00500    NPTS, DT`` (older files).  Then NPTS values in free format.
    The value count must equal NPTS.  Samples at t = k DT, k = 0..NPTS-1.
    """
    p, lines = _read_lines(path)
    expected = "'NPTS= n, DT= dt SEC' (NGA-West2) or 'n dt NPTS, DT' (older PEER)"
    if len(lines) < 4:
        raise ArchInputError(
            f"record {p.name}: missing header ({len(lines)} lines); allowed 4 header lines, the 4th {expected}"
        )
    kind = lines[2].upper()
    m_units = re.search(r"UNITS\s+OF\s+(\S+)", kind)
    if "VELOCITY" in kind or "DISPLACEMENT" in kind or (
        m_units and m_units.group(1).strip(".,;:") not in ("G", "G'S")
    ):
        raise ArchInputError(f"record {p.name}: line 3: {_short(lines[2])}; allowed an acceleration record in g")
    head = lines[3].strip()
    m = _NGA_HEADER.search(head) or _OLD_HEADER.match(head)
    if m is None:
        raise ArchInputError(f"record {p.name}: line 4: header {_short(head)}; allowed {expected}")
    npts_tok, dt_tok = m.group(1), m.group(2)
    try:
        npts = int(npts_tok)
    except ValueError:
        raise ArchInputError(f"record {p.name}: line 4: NPTS {npts_tok!r}; allowed an integer >= 2") from None
    dt = _number(p, 4, dt_tok)
    if dt <= 0.0:
        raise ArchInputError(f"record {p.name}: line 4: DT {dt:g} s; allowed > 0 s")
    if npts < 2:
        what = "empty record, " if npts <= 0 else ""
        raise ArchInputError(f"record {p.name}: line 4: {what}NPTS {npts}; allowed an integer >= 2")
    values: list[float] = []
    for lineno, raw in enumerate(lines[4:], start=5):
        for tok in raw.split():
            values.append(_number(p, lineno, tok))
    if len(values) != npts:
        few = "fewer" if len(values) < npts else "more"
        raise ArchInputError(
            f"record {p.name}: NPTS: header says {npts} but {len(values)} values found ({few}); "
            "allowed exactly NPTS values"
        )
    t = np.arange(npts) * dt
    acc = np.array(values) * G
    title = lines[1].strip()
    return GroundMotion(t, acc, title or p.stem, f"{p} (PEER AT2, g, NPTS={npts}, DT={dt:g} s)")


def load_record(path, units: str | None = None) -> GroundMotion:
    """Read a record by suffix: ``.AT2`` (any case) -> :func:`read_at2` (units must be g or None),
    anything else -> :func:`read_two_column` with ``units`` (default 'g')."""
    if not isinstance(path, (str, Path)) and not hasattr(path, "__fspath__"):
        raise ArchInputError(f"record path: {path!r}; allowed a file path")
    p = Path(path)
    if p.suffix.lower() == ".at2":
        if units is not None and units != "g":
            raise ArchInputError(f"units: {units!r} for {p.name}; allowed 'g' (PEER .AT2 values are in g)")
        return read_at2(p)
    return read_two_column(p, units="g" if units is None else units)
