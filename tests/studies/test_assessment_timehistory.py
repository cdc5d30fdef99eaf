"""The assessment's time-history verification: the codes' rule on the records' effects, the
effect of a peak rotation (the nonlinear kinematic check's capacity curve), and the section on
Oppenheim's arch with the FEMA P695 far-field set for NTC 2018 sites."""

import math

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch
from archrock.studies.assessment_timehistory import code_rule, peak_effect
from archrock.studies.codecheck import code_check


# ---------------------------------------------------------------------------- the rule
def test_seven_records_take_the_mean():
    e = [0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4]  # mean 0.8: passes although two exceed 1
    r = code_rule(e)
    assert r["rule"] == "mean" and r["n"] == 7
    assert r["value"] == pytest.approx(0.8, rel=1e-12)
    assert r["passed"] is True and r["collapsed"] == 0 and r["unbounded"] is False
    assert "(1/n) sum_i E_i <= 1" in r["formula"]
    assert code_rule([1.1] * 7)["passed"] is False


def test_five_records_take_the_largest():
    r = code_rule([0.2, 0.3, 0.4, 0.5, 1.05])  # mean 0.49 would pass; the largest governs
    assert r["rule"] == "max" and r["value"] == pytest.approx(1.05, rel=1e-12)
    assert r["passed"] is False and "max_i E_i" in r["formula"]
    assert code_rule([0.2, 0.3, 0.9])["passed"] is True


def test_one_collapse_makes_the_mean_unbounded():
    r = code_rule([0.1] * 6 + [math.inf])
    assert r["rule"] == "mean" and r["collapsed"] == 1
    assert math.isinf(r["value"]) and r["unbounded"] is True and r["passed"] is False


def test_too_few_records_or_bad_effects_are_refused():
    with pytest.raises(ArchInputError, match="^records: 2; allowed at least 3 records"):
        code_rule([0.1, 0.2])
    with pytest.raises(ArchInputError, match="^effects: allowed numbers >= 0"):
        code_rule([0.1, 0.2, float("nan")])


# ---------------------------------------------------------------------------- the effect
@pytest.fixture(scope="module")
def opp_check():
    return code_check(oppenheim_arch())


def test_effect_maps_the_peak_by_the_check_s_capacity_curve(opp_check):
    """At the rotation where the capacity curve reaches d_u* the effect is 1; at rest 0; past the
    unstable rotation d_0* / d_u* = 1 / 0.4; the larger direction's effect governs."""
    c = opp_check.direction("l")
    k = int(np.searchsorted(c.curve_d_star, c.du_star))
    # the curve's own knot nearest d_u*: its effect is its d* over d_u*, exactly
    phi = float(c.curve_rotation[k])
    e = peak_effect(opp_check.directions, {"l": phi, "r": 0.0})
    assert e["direction"] == "l"
    assert e["effect"] == pytest.approx(c.curve_d_star[k] / c.du_star, rel=1e-12)
    assert 0.9 < e["effect"] < 1.1
    assert peak_effect(opp_check.directions, {"l": 0.0, "r": 0.0})["effect"] == 0.0
    past = peak_effect(opp_check.directions, {"l": 0.0, "r": 10.0})
    assert past["direction"] == "r" and past["effect"] == pytest.approx(2.5, rel=1e-9)
