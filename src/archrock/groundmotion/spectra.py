"""Response spectra of a ground motion: Sa(T, zeta) [g] at many periods at once.

The oscillator u'' + 2 zeta omega u' + omega^2 u = -xg''(t) starts at rest.  Its exact response
to a forcing that is linear between knots (Nigam & Jennings 1969) is a fixed linear map of the
state (u, u') and the forcing at the two ends of a step; on knots equally spaced by h that map
is a 2nd-order recursive filter, which :func:`scipy.signal.lfilter` runs over the whole record
in compiled code.  The knots are the ones :func:`archrock.groundmotion.intensity.spectral_acceleration`
always used, so the two give the same number up to rounding:

* each interval of the record is cut into n = ceil(h / (T / 100)) equal pieces (the peak
  between samples is caught to within 1 - cos(pi / 100) = 5e-4 relative at worst);
* a run of equal intervals is one filter call; a step (a time repeated) or a change of interval
  starts a new run from the state reached, the forcing jumping and the state not;
* after the record, two periods of free vibration sampled at T / 100.

Sa = omega^2 max |u| / g: the pseudo-spectral acceleration.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from ..units import G
from .motion import GroundMotion

__all__ = ["response_spectrum", "PIECES_PER_PERIOD", "FREE_PERIODS"]

#: knots per period of the oscillator: the peak is sampled at most T / 100 apart
PIECES_PER_PERIOD = 100
#: periods of free vibration followed after the record
FREE_PERIODS = 2
# intervals whose lengths agree to this relative tolerance run through one filter call
# (records sampled at k dt differ in their intervals only by rounding)
_SAME_STEP_REL = 1e-9


def _runs(times: np.ndarray) -> list:
    """(first, last) sample indices of the runs of equal nonzero intervals, in time order."""
    h = np.diff(times)
    moving = h > 0.0  # a repeated time is a step: no time passes
    same = np.zeros(h.size, bool)
    same[1:] = moving[1:] & moving[:-1] & (np.abs(h[1:] - h[:-1]) <= _SAME_STEP_REL * h[:-1])
    starts = np.flatnonzero(moving & ~same)
    ends = np.append(starts[1:], h.size)
    runs = []
    for k, end in zip(starts.tolist(), ends.tolist()):
        j = k + 1
        j += int(np.argmin(same[j:end])) if not same[j:end].all() else end - j
        runs.append((k, j))
    return runs


def _free(u0, v0, t, w, z):
    """State (u, u') of the free damped oscillator at time(s) t from (u0, v0) at 0."""
    wd = w * math.sqrt(1.0 - z * z)
    e = np.exp(-z * w * t)
    c, s = np.cos(wd * t), np.sin(wd * t)
    d = (v0 + z * w * u0) / wd
    return (e * (u0 * c + d * s),
            e * ((-z * w * u0 + wd * d) * c + (-z * w * d - wd * u0) * s))


def _step_map(h: float, w: float, z: float) -> tuple:
    """Phi, Gamma0, Gamma1 of the exact step x1 = Phi x0 + Gamma0 p0 + Gamma1 p1 over h [s]
    for a forcing linear from p0 to p1 (x = (u, u'))."""
    wd = w * math.sqrt(1.0 - z * z)
    e = math.exp(-z * w * h)
    c, sn = math.cos(wd * h), math.sin(wd * h)

    def step(u, v, p0, p1):
        s = (p1 - p0) / h
        B = s / (w * w)
        A = (p0 - 2.0 * z * w * B) / (w * w)
        C = u - A
        D = (v - B + z * w * C) / wd
        return (e * (C * c + D * sn) + A + B * h,
                e * ((-z * w * C + wd * D) * c + (-z * w * D - wd * C) * sn) + B)

    phi = np.column_stack([step(1.0, 0.0, 0.0, 0.0), step(0.0, 1.0, 0.0, 0.0)])
    g0 = np.array(step(0.0, 0.0, 1.0, 0.0))
    g1 = np.array(step(0.0, 0.0, 0.0, 1.0))
    return phi, g0, g1


def _run(u0, v0, p, h, w, z):
    """Displacements at the knots of one run (forcing ``p`` at knots h apart, state (u0, v0) at
    the first) and the state at the last knot."""
    from scipy.signal import lfilter

    phi, g0, g1 = _step_map(h, w, z)
    # state y_k = x_k - Gamma1 p_k: y_{k+1} = Phi y_k + (Phi Gamma1 + Gamma0) p_k,
    # u_k = y_k[0] + Gamma1[0] p_k, a proper filter b(z)/a(z) of p
    bvec = phi @ g1 + g0
    d = g1[0]
    a = np.array([1.0, -np.trace(phi), np.linalg.det(phi)])
    b = d * a + np.array([0.0, bvec[0], phi[0, 1] * bvec[1] - phi[1, 1] * bvec[0]])
    y0 = np.array([u0, v0]) - g1 * p[0]
    # the filter's initial conditions: the outputs the state y0 had one and two steps before
    # (free vibration backwards, no forcing then)
    (u1, u2), _ = _free(y0[0], y0[1], np.array([-h, -2.0 * h]), w, z)
    # lfilter's transposed direct form holds -a1 u_-1 - a2 u_-2 and -a2 u_-1 (inputs 0 then)
    u = lfilter(b, a, p, zi=[-a[1] * u1 - a[2] * u2, -a[2] * u1])[0]
    if u.size == 1:
        return u, (u0, v0)
    # u' at the last knot, from the last two displacements and the exact step between them
    v_prev = (u[-1] - phi[0, 0] * u[-2] - g0[0] * p[-2] - g1[0] * p[-1]) / phi[0, 1]
    v_end = phi[1, 0] * u[-2] + phi[1, 1] * v_prev + g0[1] * p[-2] + g1[1] * p[-1]
    return u, (float(u[-1]), float(v_end))


def _peak_displacement(times, force, runs, T, z) -> float:
    """max |u| [m] of the oscillator of period T under the forcing ``force`` (module doc)."""
    w = 2.0 * math.pi / T
    piece = T / PIECES_PER_PERIOD
    u0 = v0 = 0.0
    peak = 0.0
    for i0, i1 in runs:
        m = i1 - i0
        h = (times[i1] - times[i0]) / m
        # an interval of exactly k pieces is k pieces, whatever its last bit (h = 0.3 / 200
        # at T = 0.15 s: h / piece is 1 or 1 + 2e-16 as the interval was rounded)
        n = max(1, math.ceil(h / piece * (1.0 - _SAME_STEP_REL)))
        fine = np.interp(np.arange(m * n + 1) / n, np.arange(m + 1), force[i0:i1 + 1])
        u, (u0, v0) = _run(u0, v0, fine, h / n, w, z)
        peak = max(peak, float(np.max(np.abs(u))))
    steps = FREE_PERIODS * PIECES_PER_PERIOD
    t = FREE_PERIODS * T * np.arange(1, steps + 1) / steps
    uf, _ = _free(u0, v0, t, w, z)
    return max(peak, float(np.max(np.abs(uf))))


def response_spectrum(motion: GroundMotion, periods, damping: float = 0.05) -> np.ndarray:
    """Pseudo-spectral accelerations Sa(T) = omega^2 max |u| [g], one per period [s] of
    ``periods``, of oscillators with ``damping`` (ratio of critical) under ``motion``."""
    if not isinstance(motion, GroundMotion):
        raise ArchInputError(f"motion: {type(motion).__name__}; allowed a GroundMotion")
    try:
        T = np.array(periods, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ArchInputError(f"periods: {periods!r}; allowed numbers > 0 s") from None
    if T.size == 0 or not np.all(np.isfinite(T)) or np.any(T <= 0.0):
        raise ArchInputError(f"periods: {np.array2string(T, threshold=6)}; allowed one or more "
                             f"numbers > 0 s")
    try:
        z = float(damping)
    except (TypeError, ValueError):
        z = math.nan
    if not (math.isfinite(z) and 0.0 <= z < 1.0):
        raise ArchInputError(f"damping: {damping!r}; allowed 0 <= damping < 1")
    times = np.asarray(motion.times, float)
    force = -np.asarray(motion.accel, float)
    runs = _runs(times)
    out = np.empty(T.size)
    for k, Tk in enumerate(T):
        w = 2.0 * math.pi / Tk
        out[k] = w * w * _peak_displacement(times, force, runs, float(Tk), z) / G
    return out
