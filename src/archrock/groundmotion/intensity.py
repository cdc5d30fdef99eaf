"""Intensity measures (IM) of a ground motion, for fragility curves.

Every measure is computed exactly for the piecewise-linear acceleration of a
:class:`~archrock.groundmotion.GroundMotion` (zero before t = 0 and after the last sample):

* ``pga``: peak ground acceleration max |xg''| [g];
* ``pgv``: peak ground velocity max |xg'| [m/s], xg' the integral of xg'' from rest (no baseline
  correction): piecewise quadratic, so its extremes are at the samples and where xg'' changes
  sign inside an interval.  Rocking collapse of large blocks and arches scales with a velocity
  rather than an acceleration (Housner 1963; Makris & Konstantinidis 2003), which makes PGV a
  natural IM for rocking;
* ``sa:T``: pseudo-spectral acceleration Sa(T, 5%) = omega^2 max |u| [g] of a linear oscillator
  u'' + 2 zeta omega u' + omega^2 u = -xg'' of period T [s] and damping zeta = 0.05, starting at
  rest, integrated exactly interval by interval (the closed-form solution for a linear forcing,
  Nigam & Jennings 1969), each interval cut into pieces of at most T/100 where the peak is
  sampled, and followed for two periods of free vibration after the record
  (:func:`archrock.groundmotion.spectra.response_spectrum`, which gives many periods at once);
* ``arias``: Arias intensity I_A = pi / (2 g) int xg''^2 dt [m/s] (Arias 1970);
* ``scale``: the scale factor itself (records normalised beforehand).

Scaling a record by s multiplies pga, pgv and sa by |s| and arias by s^2 (:func:`im_at`,
:func:`scale_for`).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from ..units import G
from .motion import GroundMotion
from .spectra import response_spectrum

__all__ = ["IM_NAMES", "parse_im", "im_units", "im_label", "im_power", "intensity", "im_at",
           "scale_for", "pga", "pgv", "arias_intensity", "spectral_acceleration"]

#: the measures :func:`parse_im` reads (``sa`` with its period: ``sa:1.0``)
IM_NAMES = ("pga", "pgv", "sa:T", "arias", "scale")
#: the damping ratio of Sa
SA_DAMPING = 0.05
#: periods of Sa accepted [s]: beyond them the oscillator is not a structure's
SA_PERIODS = (0.01, 20.0)


def parse_im(im) -> str:
    """The canonical name of an IM: 'pga', 'pgv', 'arias', 'scale' or 'sa:T' (T in s, written
    with ``repr`` of the float), or ArchInputError naming the field and what is allowed."""
    if not isinstance(im, str):
        raise ArchInputError(f"im: {im!r}; allowed one of {', '.join(IM_NAMES)}")
    key = im.strip().lower()
    if key in ("pga", "pgv", "arias", "scale"):
        return key
    if key.startswith("sa:") or key.startswith("sa(") or key == "sa":
        text = key[3:].rstrip(")") if key != "sa" else ""
        try:
            T = float(text)
        except ValueError:
            raise ArchInputError(f"im: {im!r}: the period of Sa is missing or not a number; "
                                 f"allowed sa:T with T in s, {SA_PERIODS[0]:g} <= T <= "
                                 f"{SA_PERIODS[1]:g} (e.g. sa:1.0)") from None
        if not (math.isfinite(T) and SA_PERIODS[0] <= T <= SA_PERIODS[1]):
            raise ArchInputError(f"im: {im!r}: Sa period {T:g} s; allowed {SA_PERIODS[0]:g} <= T "
                                 f"<= {SA_PERIODS[1]:g} s")
        return f"sa:{T!r}"
    raise ArchInputError(f"im: {im!r}; allowed one of {', '.join(IM_NAMES)} (T: period in s)")


def _period(im: str) -> float:
    return float(im.split(":", 1)[1])


def im_units(im: str) -> str:
    """Units of the IM's values: 'g', 'm/s' or '-'."""
    im = parse_im(im)
    return {"pga": "g", "pgv": "m/s", "arias": "m/s", "scale": "-"}.get(im, "g")


def im_label(im: str) -> str:
    """Axis label of the IM, e.g. 'Sa(1 s, 5%) of the scaled record [g]'."""
    im = parse_im(im)
    if im.startswith("sa:"):
        return f"Sa({_period(im):g} s, {100 * SA_DAMPING:g}%) of the scaled record [g]"
    return {"pga": "PGA of the scaled record [g]", "pgv": "PGV of the scaled record [m/s]",
            "arias": "Arias intensity of the scaled record [m/s]",
            "scale": "scale factor [-]"}[im]


def im_power(im: str) -> int:
    """The exponent p of IM(s x record) = |s|^p IM(record): 2 for Arias, else 1."""
    return 2 if parse_im(im) == "arias" else 1


# ---------------------------------------------------------------------------- measures
def pga(motion: GroundMotion) -> float:
    """Peak ground acceleration [g]."""
    return float(np.max(np.abs(motion.accel))) / G if motion.accel.size else 0.0


def _velocity(motion: GroundMotion) -> np.ndarray:
    """xg' [m/s] at the samples (exact: trapezoids of a piecewise-linear xg'')."""
    t, a = motion.times, motion.accel
    v = np.zeros(t.size)
    v[1:] = np.cumsum(0.5 * (a[1:] + a[:-1]) * np.diff(t))
    return v


def pgv(motion: GroundMotion) -> float:
    """Peak ground velocity [m/s] (module doc)."""
    t, a = np.asarray(motion.times, float), np.asarray(motion.accel, float)
    if t.size == 0:
        return 0.0
    v = _velocity(motion)
    peak = float(np.max(np.abs(v)))
    h = np.diff(t)
    a0, a1 = a[:-1], a[1:]
    # an extreme of v inside an interval where xg'' changes sign: v(t0 + x) with a(x) = 0
    cross = np.flatnonzero((a0 * a1 < 0) & (h > 0))
    if cross.size:
        x = h[cross] * a0[cross] / (a0[cross] - a1[cross])
        vx = v[:-1][cross] + 0.5 * a0[cross] * x
        peak = max(peak, float(np.max(np.abs(vx))))
    return peak


def arias_intensity(motion: GroundMotion) -> float:
    """Arias intensity [m/s]: pi / (2 g) int xg''^2 dt, exact for a piecewise-linear xg''."""
    t, a = np.asarray(motion.times, float), np.asarray(motion.accel, float)
    if t.size < 2:
        return 0.0
    h = np.diff(t)
    a0, a1 = a[:-1], a[1:]
    return float(math.pi / (2.0 * G) * np.sum(h * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0))


def spectral_acceleration(motion: GroundMotion, period: float,
                          damping: float = SA_DAMPING) -> float:
    """Pseudo-spectral acceleration omega^2 max |u| [g] of the oscillator of ``period`` [s]
    and ``damping`` (module doc)."""
    T = float(period)
    if not (math.isfinite(T) and T > 0):
        raise ArchInputError(f"period: {period!r}; allowed a number > 0 s")
    z = float(damping)
    if not (math.isfinite(z) and 0 <= z < 1):
        raise ArchInputError(f"damping: {damping!r}; allowed 0 <= damping < 1")
    return float(response_spectrum(motion, [T], z)[0])


def intensity(motion: GroundMotion, im: str) -> float:
    """The IM ``im`` (:func:`parse_im`) of ``motion`` as it is (scale factor 1)."""
    im = parse_im(im)
    if im == "pga":
        return pga(motion)
    if im == "pgv":
        return pgv(motion)
    if im == "arias":
        return arias_intensity(motion)
    if im == "scale":
        return 1.0
    return spectral_acceleration(motion, _period(im))


def im_at(unit_value: float, im: str, scale: float) -> float:
    """IM of the record scaled by ``scale``, from its IM at scale 1 (``unit_value``)."""
    return unit_value * abs(scale) ** im_power(im)


def scale_for(unit_value: float, im: str, level: float) -> float:
    """Scale factor that brings a record of IM ``unit_value`` (at scale 1) to ``level``."""
    if not unit_value > 0:
        raise ArchInputError(f"im: the record's {im} is {unit_value:g}; allowed a record with a "
                             f"nonzero intensity")
    return (level / unit_value) ** (1.0 / im_power(im))
