"""Random arches of finite compressive strength (geometry.sampling): every drawn arch keeps the
nominal's f_c, ``Spreads.fc`` draws each arch's f_c on its own stream (the blocks' draws do not
change), and without a strength nothing changes, hashes included."""

import numpy as np
import pytest

from archrock.errors import ArchInputError, InvalidSampleError
from archrock.geometry import family_arch, oppenheim_arch
from archrock.geometry.sampling import ArchSampler, Spreads


def test_drawn_arches_keep_the_nominal_strength_and_the_blocks():
    plain = ArchSampler(oppenheim_arch(), seed=4)
    strong = ArchSampler(oppenheim_arch().with_fc(5.0), seed=4)
    assert strong.finite and not plain.finite
    for a, b in zip(plain.arches(0, 5), strong.arches(0, 5)):
        assert a.fc is None and b.fc == pytest.approx(5.0, rel=0, abs=0)
        assert np.array_equal(a.joint_points, b.joint_points)
        assert np.array_equal(a.masses, b.masses)
    assert strong.arch(3).fc == pytest.approx(5.0, rel=0, abs=0)


def test_strength_spread_draws_fc_on_its_own_stream():
    fam = oppenheim_arch().with_fc(5.0)  # exact sectors: no compiled family draws
    plain = ArchSampler(fam, Spreads(0.1, 0.1, 0.05), seed=2)
    spread = ArchSampler(fam, Spreads(0.1, 0.1, 0.05, fc=0.4), seed=2)
    drawn = spread.arches(0, 8)
    u = spread.strength_uniforms(0, 8)
    fcs = np.array([a.fc for a in drawn])
    assert np.allclose(fcs, 5.0 * (1.0 + 0.4 * u), rtol=1e-15, atol=0)
    assert fcs.min() >= 3.0 - 1e-12 and fcs.max() <= 7.0 + 1e-12 and np.ptp(fcs) > 0.5
    for a, b in zip(plain.arches(0, 8), drawn):
        assert np.array_equal(a.joint_points, b.joint_points)
    # one arch alone is the same as in the list
    assert spread.arch(5).fc == pytest.approx(fcs[5], rel=1e-15, abs=0)


def test_strength_spread_needs_a_strength():
    with pytest.raises(ArchInputError, match=r"^spread fc: 0\.2 .*allowed 0"):
        ArchSampler(oppenheim_arch(), Spreads(fc=0.2))
    with pytest.raises(ArchInputError, match=r"^spread fc: 1\.5; allowed 0 <= s < 1"):
        Spreads(fc=1.5)


def test_a_draw_below_the_strengths_allowed_is_an_invalid_sample():
    sampler = ArchSampler(oppenheim_arch().with_fc(0.11), Spreads(fc=0.9), seed=0)
    drawn = sampler.arches(0, 40)
    bad = [a for a in drawn if isinstance(a, Exception)]
    assert bad and all(isinstance(a, InvalidSampleError) and "fc" in str(a) for a in bad)


def test_without_strength_the_spreads_dict_is_unchanged():
    s = Spreads(0.1, 0.1, 0.05)
    assert "fc" not in s.to_dict() and "fc" not in s.legacy_dict()
    assert Spreads.from_dict({**s.to_dict(), "fc": 0.25}).fc == pytest.approx(0.25, rel=0, abs=0)
    assert Spreads(fc=0.25).to_dict()["fc"] == pytest.approx(0.25, rel=0, abs=0)


@pytest.mark.slow
def test_family_draws_keep_the_strength():
    """The compiled family draws (exact=False) carry f_c too (slow: their first compile)."""
    fam = family_arch("circular", 10.0, 1.5, 0.5, 15, exact=False, fc=5.0)
    drawn = ArchSampler(fam, Spreads(0.1, 0.1, 0.05, fc=0.4), seed=2).arches(0, 8)
    fcs = np.array([a.fc for a in drawn])
    assert fcs.min() >= 3.0 - 1e-12 and fcs.max() <= 7.0 + 1e-12 and np.ptp(fcs) > 0.5
