"""The one sampler of random arches: sample i depends on (nominal, spreads, seed, i) only."""

import numpy as np
import pytest

from archrock.errors import ArchInputError, InvalidSampleError
from archrock.geometry import nominal_arch, oppenheim_arch, perturb_voussoirs
from archrock.geometry.sampling import BLOCK, DEFAULT_SPREADS, ArchSampler, Spreads


def test_sample_is_independent_of_how_the_draws_are_cut():
    s = ArchSampler(oppenheim_arch(), DEFAULT_SPREADS, seed=3)
    whole = s.uniforms(0, 2 * BLOCK + 7)
    for start, count in ((0, 1), (BLOCK - 2, 5), (BLOCK, 3), (2 * BLOCK + 3, 4), (17, 900)):
        assert np.array_equal(s.uniforms(start, count), whole[start:start + count])
    spans, thick, radii = s.draw(BLOCK + 1, 1)
    arch = s.arch(BLOCK + 1)
    assert np.array_equal(arch.spans, spans[0]) and np.array_equal(arch.radii, radii[0])


def test_streams_are_the_documented_seed_sequences():
    """Block k reads SeedSequence(seed, spawn_key=(k,)) from its start (0.1.0's ensemble streams)."""
    nom = oppenheim_arch()
    s = ArchSampler(nom, Spreads(0.2, 0.1, 0.05), seed=11)
    rng = np.random.default_rng(np.random.SeedSequence(11, spawn_key=(1,)))
    u = rng.uniform(-1.0, 1.0, size=(4, 3, nom.n))
    assert np.array_equal(s.uniforms(BLOCK + 2, 2), u[2:4])
    spans, thick, radii = perturb_voussoirs(nom.spans, nom.thicknesses, nom.radii, u[3], 0.2, 0.1, 0.05)
    a = s.arch(BLOCK + 3)
    assert np.allclose(a.spans, spans, rtol=0, atol=0) and np.array_equal(a.thicknesses, thick)
    assert a.embrace == pytest.approx(nom.embrace, rel=1e-14)


def test_zero_spreads_give_the_nominal_arch_and_seeds_differ():
    nom = nominal_arch(5.0, 160.0, 0.6, 9)
    a = ArchSampler(nom, Spreads(0, 0, 0), seed=1).arch(42)
    assert np.allclose(a.spans, nom.spans, rtol=1e-14) and np.array_equal(a.radii, nom.radii)
    assert not np.array_equal(ArchSampler(nom, seed=1).arch(0).spans, ArchSampler(nom, seed=2).arch(0).spans)


def test_spreads_and_sampler_refuse_bad_fields():
    with pytest.raises(ArchInputError, match="^spread span"):
        Spreads(span=1.0)
    with pytest.raises(ArchInputError, match="^spread radius"):
        Spreads.from_dict({"spread_radius": float("nan")})
    with pytest.raises(ArchInputError, match="^spreads: unknown"):
        Spreads.from_dict({"spread_rise": 0.1})
    with pytest.raises(ArchInputError, match="^seed"):
        ArchSampler(oppenheim_arch(), seed=-1)
    assert Spreads.from_dict(DEFAULT_SPREADS.to_dict()) == DEFAULT_SPREADS


def test_invalid_draw_is_a_geometry_outcome():
    s = ArchSampler(oppenheim_arch(), Spreads(0.1, 0.99, 0.99), seed=27)
    with pytest.raises(InvalidSampleError, match="^not a valid arch: joint"):
        s.arch(2)
