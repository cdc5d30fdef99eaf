"""Idealised pulses (Oppenheim's, rectangular, half-sine, one-sine, Ricker) as GroundMotions.

Amplitudes are in g (multiples of ``G``) and may be negative: the paper's forcing is Oppenheim's
pulse with a = -1 g, t_p = 0.20 s.  Durations and periods in s.
"""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError
from ..units import G
from .motion import MAX_PGA_G, GroundMotion, _count, _positive, _real

__all__ = ["PULSE_KINDS", "oppenheim_pulse", "rectangular_pulse", "half_sine_pulse",
           "one_sine_pulse", "ricker_pulse", "pulse", "pulse_kind"]

#: Pulse kinds accepted by :func:`pulse`.
PULSE_KINDS = ("oppenheim", "rectangular", "half-sine", "one-sine", "ricker")

_MIN_SAMPLES = 4  # smallest number of intervals for the sampled pulses
#: Range of a pulse's duration or period [s]: an arch's own times scale with the square root of
#: its size, so 0.2 s at 10 m is 6e-6 s at the smallest arch (1e-8 m) and 600 s at the largest
#: (1e8 m); outside the range the number is a slip, and 1e-300 or 1e300 s hung the integrator.
MIN_PULSE_S, MAX_PULSE_S = 1e-6, 1e4


def _duration(field: str, value) -> float:
    """A pulse duration or period [s] in [MIN_PULSE_S, MAX_PULSE_S]."""
    tp = _positive(field, value)
    if not MIN_PULSE_S <= tp <= MAX_PULSE_S:
        raise ArchInputError(f"{field}: {tp:g} s is out of range; allowed {MIN_PULSE_S:g} s to "
                             f"{MAX_PULSE_S:g} s")
    return tp


def _amplitude(value) -> float:
    """A pulse amplitude [g]: finite and at most MAX_PGA_G in size (no pulse above it can be
    meant, and the rocking kernel breaks down far above it)."""
    ag = _real("pulse amplitude", value, "g")
    if abs(ag) > MAX_PGA_G:
        raise ArchInputError(f"pulse amplitude: {ag:g} g; allowed at most {MAX_PGA_G:g} g in "
                             f"size (the strongest earthquakes reach about 3-4 g)")
    return ag


def oppenheim_pulse(amplitude_g: float = -1.0, duration: float = 0.2) -> GroundMotion:
    """Oppenheim's idealised pulse (the paper's forcing, a = -1 g, t_p = 0.2 s).

    xg'' = a on [0, t_p), -a/2 on [t_p, 3 t_p), 0 from 3 t_p on; encoded exactly with steps:
    times [0, t_p, t_p, 3 t_p, 3 t_p], accel [a, a, -a/2, -a/2, 0].  Zero net velocity change.
    """
    ag = _amplitude(amplitude_g)
    a = ag * G
    tp = _duration("pulse duration", duration)
    t = [0.0, tp, tp, 3.0 * tp, 3.0 * tp]
    acc = [a, a, -0.5 * a, -0.5 * a, 0.0]
    return GroundMotion(
        np.array(t), np.array(acc), "Oppenheim pulse",
        f"oppenheim pulse: a = {ag:g} g, t_p = {tp:g} s",
    )


def rectangular_pulse(amplitude_g: float, duration: float) -> GroundMotion:
    """xg'' = a on [0, t_p), 0 from t_p on (times [0, t_p, t_p], accel [a, a, 0])."""
    ag = _amplitude(amplitude_g)
    a = ag * G
    tp = _duration("pulse duration", duration)
    return GroundMotion(
        np.array([0.0, tp, tp]), np.array([a, a, 0.0]), "rectangular pulse",
        f"rectangular pulse: a = {ag:g} g, t_p = {tp:g} s",
    )


def half_sine_pulse(amplitude_g: float, duration: float, samples_per_pulse: int = 200) -> GroundMotion:
    """xg'' = a sin(pi t / t_p) on [0, t_p], 0 after; ``samples_per_pulse`` intervals.

    Velocity change 2 a t_p / pi.
    """
    ag = _amplitude(amplitude_g)
    a = ag * G
    tp = _duration("pulse duration", duration)
    n = _count("samples per pulse", samples_per_pulse, _MIN_SAMPLES)
    t = np.linspace(0.0, tp, n + 1)
    acc = a * np.sin(np.pi * t / tp)
    acc[0] = acc[-1] = 0.0  # exact zeros instead of a * sin(pi) ~ 1e-16 a
    return GroundMotion(t, acc, "half-sine pulse", f"half-sine pulse: a = {ag:g} g, t_p = {tp:g} s")


def one_sine_pulse(amplitude_g: float, duration: float, samples_per_pulse: int = 400) -> GroundMotion:
    """xg'' = a sin(2 pi t / t_p) on [0, t_p] (one full cycle), 0 after.

    Zero net velocity change; ``samples_per_pulse`` intervals.
    """
    ag = _amplitude(amplitude_g)
    a = ag * G
    tp = _duration("pulse duration", duration)
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
    ag = _amplitude(amplitude_g)
    a = ag * G
    T = _duration("pulse period", period)
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

