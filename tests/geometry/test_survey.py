"""Irregular arches around a surveyed polygon arch (geometry.survey): joints stay, thickness and
centreline offset vary as the family arches' do."""

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import Arch, as_polygon, oppenheim_arch, perturb_voussoirs
from archrock.geometry.sampling import ArchSampler, Spreads
from archrock.geometry.survey import perturb_survey
from archrock.statics.limit import limit_analysis

U = np.random.default_rng(4).uniform(-1.0, 1.0, size=(3, 7))


@pytest.fixture(scope="module")
def survey():
    return as_polygon(oppenheim_arch())  # a polygon arch without a family recipe


def test_a_circular_survey_moves_as_the_circular_arch_does(survey):
    """On a circular arch the rule is the circular sampler's: t_i = t (1 + s_t U1), R_i = R +
    s_R t U2, voussoir for voussoir (the span row unused): the same polygon to rounding."""
    nom = oppenheim_arch()
    spans, thick, radii = perturb_voussoirs(nom.spans, nom.thicknesses, nom.radii, U, 0.0, 0.1,
                                            0.05)
    ref = as_polygon(Arch(spans, radii, thick, nom.density))
    got = perturb_survey(survey, U, 0.1, 0.05)
    for a, b in zip(got.intrados + got.extrados, ref.intrados + ref.extrados):
        assert np.max(np.abs(a - b)) < 1e-12 * nom.size
    assert limit_analysis(got).k == pytest.approx(limit_analysis(ref).k, rel=1e-9)


def test_joints_stay_on_their_surveyed_lines(survey):
    got = perturb_survey(survey, U, 0.3, 0.2)
    for j in range(1, survey.n):
        p, q = survey.intrados[j][0], survey.extrados[j][0]
        d = (q - p) / np.hypot(*(q - p))
        for pt in (got.intrados[j - 1][-1], got.intrados[j][0], got.extrados[j - 1][-1],
                   got.extrados[j][0]):
            v = pt - p
            assert abs(d[0] * v[1] - d[1] * v[0]) < 1e-12 * survey.size
    zero = perturb_survey(survey, U, 0.0, 0.0)
    assert all(np.array_equal(a, b) for a, b in zip(zero.intrados, survey.intrados))


def test_the_sampler_takes_a_survey_and_refuses_span_and_tilt(survey):
    with pytest.raises(ArchInputError, match="spread span and tilt: 0.1 and 0; allowed 0 and 0"):
        ArchSampler(survey)
    sampler = ArchSampler(survey, Spreads(0.0, 0.1, 0.05), seed=3)
    assert limit_analysis(ArchSampler(survey, Spreads(0.0, 0.0, 0.0)).arch(5)).k == \
        pytest.approx(limit_analysis(survey).k, rel=1e-12)
    ks = [limit_analysis(sampler.arch(i)).k for i in range(6)]
    assert len(set(ks)) == 6 and all(0.25 < k < 0.45 for k in ks)
    assert [a.name for a in sampler.arches(2, 2)] == ["sample 2", "sample 3"]


def test_an_ensemble_around_a_survey_is_its_samples(survey):
    pytest.importorskip("pandas")
    from archrock.studies.ensemble import EnsembleConfig, run_ensemble

    cfg = EnsembleConfig(nominal=survey, samples=4, seed=3, batch_size=2,
                         spreads=Spreads(0.0, 0.1, 0.05))
    res = run_ensemble(cfg)
    sampler = ArchSampler(survey, Spreads(0.0, 0.1, 0.05), seed=3)
    for i in range(4):
        lim = limit_analysis(sampler.arch(i))
        assert res.frame["k_l"][i] == pytest.approx(lim.k_l, rel=1e-9)
        assert res.frame["k_r"][i] == pytest.approx(lim.k_r, rel=1e-9)
