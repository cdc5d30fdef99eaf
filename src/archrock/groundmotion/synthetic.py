"""Synthetic records: seeded band-limited noise, the stand-in accelerogram of the tests,
benchmarks and documentation figures where no real record is at hand (no file to ship)."""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError
from .motion import GroundMotion, _count, _positive, check_pga, from_samples


def band_limited_noise(duration: float, dt: float, band: tuple[float, float], seed: int,
                       pga_g: float, name: str | None = None) -> GroundMotion:
    """White noise of ``seed`` through a 2nd-order Butterworth band-pass ``band`` = (f_lo, f_hi)
    [Hz], under a sin^2 envelope over ``duration`` [s] (zero at both ends), sampled every ``dt``
    [s] and scaled to a PGA of ``pga_g`` [g] (name default ``"noise SEED"``).

    The same arguments give the same record on every machine numpy's generator runs on."""
    from scipy.signal import butter, sosfilt

    duration, dt = _positive("duration", duration), _positive("dt", dt)
    seed = _count("seed", seed, 0)
    n = int(duration / dt)
    if n < 2:
        raise ArchInputError(f"duration: {duration:g} s; allowed at least 2 samples of dt = "
                             f"{dt:g} s")
    lo, hi = (_positive("band", f, "Hz") for f in band)
    nyquist = 0.5 / dt
    if not lo < hi < nyquist:
        raise ArchInputError(f"band: ({lo:g}, {hi:g}) Hz; allowed 0 < f_lo < f_hi < "
                             f"{nyquist:g} Hz (the Nyquist frequency of dt)")
    pga_g = _positive("pga_g", pga_g, "g")
    check_pga(pga_g, "band_limited_noise", "pga_g is in g")
    rng = np.random.default_rng(seed)
    sos = butter(2, [lo, hi], btype="band", fs=1 / dt, output="sos")
    x = sosfilt(sos, rng.standard_normal(n))
    t = np.arange(n) * dt
    x *= np.sin(np.pi * t / duration) ** 2  # a smooth start and end: no step at t = 0
    return from_samples(x * pga_g / np.max(np.abs(x)), dt,
                        name=f"noise {seed}" if name is None else name)
