"""Intensity measures: analytic values (sine pulses, resonance), a cross-check of Sa against
scipy's lsim, scaling laws, the option's validation, and fragility in each IM."""

import math

import numpy as np
import pytest
from scipy.signal import lsim

from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.groundmotion import G, from_samples, pulse
from archrock.groundmotion.intensity import (arias_intensity, im_at, intensity, parse_im, pga,
                                             pgv, scale_for, spectral_acceleration)
from archrock.studies.ida import ida, msa
from archrock.dynamics.response import prepare


def sine(amplitude_g, period, cycles, dt):
    t = np.arange(int(round(cycles * period / dt)) + 1) * dt
    return from_samples(amplitude_g * np.sin(2 * np.pi * t / period), dt, name="sine")


def test_pgv_of_sine_pulses():
    # half-sine a sin(pi t / t_p): v peaks at the end, 2 a t_p / pi; the pulse is sampled with
    # n = 200 intervals, whose linear interpolant integrates to exactly
    # a (t_p / n) sum_k sin(pi k / n) = a (t_p / n) cot(pi / (2 n)), 2e-5 below the sine's
    a, tp = 0.5, 0.4
    hs = pgv(pulse("half-sine", a, tp))
    assert hs == pytest.approx(a * G * tp / 200 / math.tan(math.pi / 400), rel=1e-12)
    assert hs == pytest.approx(2 * a * G * tp / math.pi, rel=3e-5)
    # one full sine cycle of period T (400 intervals): v = a T / (2 pi) (1 - cos), peak
    # a T / pi at T / 2; the interpolant's: a (T / 400) cot(pi / 400)
    os_ = pgv(pulse("one-sine", a, tp))
    assert os_ == pytest.approx(a * G * tp / 400 / math.tan(math.pi / 400), rel=1e-12)
    assert os_ == pytest.approx(a * G * tp / math.pi, rel=3e-5)
    # rectangular pulse: v = a t_p exactly; Oppenheim's: a t_p, then back to 0 at 3 t_p
    assert pgv(pulse("rectangular", a, tp)) == pytest.approx(a * G * tp, rel=1e-14)
    assert pgv(pulse("oppenheim", -a, tp)) == pytest.approx(a * G * tp, rel=1e-14)


def test_pgv_between_samples():
    # a triangle +a -> -a over one interval: v peaks where xg'' = 0, inside it
    from archrock.groundmotion import GroundMotion

    gm = GroundMotion(np.array([0.0, 1.0]), np.array([2.0, -2.0]))
    assert pgv(gm) == pytest.approx(0.5, rel=1e-14)  # int_0^0.5 (2 - 4 t) dt; back to 0 at 1


def test_arias_intensity():
    # constant-amplitude sine over whole cycles: pi / (2 g) A^2 D / 2
    A, T, n = 0.3, 0.5, 20
    gm = sine(A, T, n, T / 400)
    assert arias_intensity(gm) == pytest.approx(math.pi / (2 * G) * (A * G) ** 2 * n * T / 2,
                                                rel=1e-4)
    # a rectangular pulse: exact
    a, tp = 0.4, 0.3
    assert arias_intensity(pulse("rectangular", a, tp)) == pytest.approx(
        math.pi / (2 * G) * (a * G) ** 2 * tp, rel=1e-13)


def test_sa_at_resonance_and_against_lsim():
    # resonance, 40 cycles: the envelope 1 - exp(-zeta w t) has reached 1 - 3e-6, so
    # Sa = w^2 u_max -> A / (2 zeta) = 10 A
    A, T = 0.2, 0.8
    gm = sine(A, T, 40, T / 200)
    assert spectral_acceleration(gm, T) == pytest.approx(A / (2 * 0.05), rel=2e-3)
    # a rigid oscillator (T -> 0) follows the ground: Sa -> PGA
    rng = np.random.default_rng(0)
    rec = from_samples(np.convolve(rng.standard_normal(800), np.ones(8) / 8, "same") * 0.3, 0.01)
    assert spectral_acceleration(rec, 0.01) == pytest.approx(pga(rec), rel=2e-2)
    # a general record against scipy's lsim (linear interpolation of the input: exact for a
    # piecewise-linear record), on a grid 20x finer than the record, plus the free vibration
    for T in (0.3, 1.0, 2.5):
        w = 2 * np.pi / T
        t = np.arange(0, rec.times[-1] + 2 * T, 0.0005)
        u = np.interp(t, rec.times, rec.accel, right=0.0)
        _, y, _ = lsim(([-1.0], [1.0, 2 * 0.05 * w, w * w]), u, t)
        ref = w * w * np.max(np.abs(y)) / G
        assert spectral_acceleration(rec, T) == pytest.approx(ref, rel=1e-3), T


def test_scaling_laws_and_parse():
    gm = pulse("half-sine", 0.3, 0.5)
    for im in ("pga", "pgv", "sa:0.5", "arias"):
        u = intensity(gm, im)
        assert intensity(gm.scaled(2.5), im) == pytest.approx(im_at(u, im, 2.5), rel=1e-9)
        assert scale_for(u, im, im_at(u, im, 2.5)) == pytest.approx(2.5, rel=1e-12)
    assert parse_im(" SA:1 ") == "sa:1.0" and parse_im("pgv") == "pgv"
    for bad, what in (("sa", "period"), ("sa:", "period"), ("sa:x", "period"),
                      ("sa:-1", "0.01"), ("sa:100", "20"), ("pgd", "allowed"), (3, "allowed")):
        with pytest.raises(ArchInputError, match="im") as e:
            parse_im(bad)
        assert what in str(e.value)


def test_fragility_in_each_im_same_collapses():
    model = prepare(nominal_arch(radius=2.0, thickness=0.3))
    recs = [pulse("half-sine", 0.3, 0.3), pulse("one-sine", 0.3, 0.4)]
    scales = np.linspace(1.0, 8.0, 8)
    base = ida(recs, model, scales)
    for im in ("pgv", "sa:1.0", "arias"):
        res = ida(recs, model, scales, im=im)
        for c, b, r in zip(res.curves, base.curves, recs):
            assert c.first_scale == b.first_scale  # the search is in the scale factor
            if c.first_scale is not None:
                assert c.first_im == pytest.approx(im_at(intensity(r, im), im, c.first_scale))
        assert res.to_dict()["im"] == im
    # stripes at Arias levels: each record scaled by sqrt(level / its Arias intensity)
    lv = [0.05, 0.2, 0.8]
    st = msa(recs, model, lv, im="arias")
    for i, x in enumerate(lv):
        for k, r in enumerate(recs):
            s = math.sqrt(x / arias_intensity(r))
            direct = ida([r], model, [s], tol=0.5).curves[0].collapsed[0]
            assert st.outcomes[i, 0, k] == direct
    with pytest.raises(ArchInputError, match="im"):
        ida(recs, model, scales, im="sa:0")
