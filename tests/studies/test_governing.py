"""studies.governing: one decision of the governing capacity (issue 30)."""

from __future__ import annotations

import pytest

from archrock.geometry import family_arch, oppenheim_arch
from archrock.statics.limit import limit_analysis
from archrock.studies import governing as gv
from archrock.studies.governing import (ENGINE, NO_SLIDING, WITH_FRICTION, GoverningCapacity,
                                        governing_capacity)


@pytest.fixture(scope="module")
def opp():
    arch = oppenheim_arch()
    return arch, limit_analysis(arch, verify=True)


def test_oppenheim_default_friction_no_sliding_governs(opp):
    """mu 0.8 >= 0.49513 (the friction the collapse needs): k = 0.370010 from the no-sliding
    analysis, both directions; the friction analysis ran and agrees; the engine left out."""
    arch, lim = opp
    g = governing_capacity(arch, 0.8, limit=lim)
    assert isinstance(g, GoverningCapacity) and g.friction == pytest.approx(0.8, abs=1e-15)
    gov = g.governing
    assert gov.value == pytest.approx(0.370010, abs=5e-7)
    assert gov.analysis == NO_SLIDING and gov.direction == "both"
    assert "no sliding (checked against mu = 0.8)" in gov.hypotheses
    ns = g.analysis(NO_SLIDING)
    assert ns.holds == {"l": True, "r": True} and "0.4951" in ns.why["l"]
    fr = g.analysis(WITH_FRICTION)
    assert fr.k_l == pytest.approx(0.370010, abs=5e-7)
    assert dict(g.left_out)[ENGINE] == gv.ENGINE_NOT_ASKED
    assert g.line().startswith("governing: k = 0.370010 g (limit analysis (no sliding), "
                               "both directions")
    d = g.to_dict()
    assert d["governing"]["value"] == pytest.approx(0.370010, abs=5e-7)
    assert [a["name"] for a in d["analyses"]] == [NO_SLIDING, f"{WITH_FRICTION} mu = 0.8"]
    assert d["findings"] == []


def test_oppenheim_low_friction_sliding_governs(opp):
    """mu 0.4 < 0.49513: the no-sliding k does not hold; the friction analysis's 0.2638
    governs, its mechanism sliding (at the springing joints 7 and 0)."""
    arch, lim = opp
    g = governing_capacity(arch, 0.4, limit=lim)
    assert g.governing.value == pytest.approx(0.2638, abs=5e-5)
    assert g.governing.analysis == f"{WITH_FRICTION} mu = 0.4"
    assert g.governing.direction == "both"
    assert "sliding at joint(s) 7" in g.governing.mechanism
    ns = g.analysis(NO_SLIDING)
    assert ns.holds == {"l": False, "r": False} and "joints slide first" in ns.why["r"]


def test_friction_none_is_heyman_stated(opp):
    """Sliding excluded by the user: 0.370010 on Heyman's hypothesis, the friction analysis
    left out with the reason."""
    arch, lim = opp
    g = governing_capacity(arch, None, limit=lim)
    assert g.friction is None and g.governing.value == pytest.approx(0.370010, abs=5e-7)
    assert g.analysis(WITH_FRICTION) is None
    assert "sliding excluded by the user" in dict(g.left_out)[WITH_FRICTION]
    assert g.to_dict()["friction_words"].startswith("sliding excluded by the user")


def test_bad_friction_is_refused(opp):
    from archrock.errors import ArchInputError

    arch, lim = opp
    with pytest.raises(ArchInputError, match="friction"):
        governing_capacity(arch, -1.0, limit=lim)


def test_mirror_symmetry_of_a_symmetric_arch():
    """A symmetric family arch: the same multiplier both ways, so the governing direction is
    'both', whichever analysis governs."""
    arch = family_arch("circular", 10, 1.5, 0.5, 15)
    assert arch.is_symmetric()
    for mu in (0.8, 0.5):
        g = governing_capacity(arch, mu)
        for a in g.analyses:
            assert a.k_l == pytest.approx(a.k_r, rel=1e-7)
        assert g.governing.direction == "both"
    assert governing_capacity(arch, 0.8).governing.value == pytest.approx(1.9045, abs=5e-5)


class _RD:
    """A stand-in for contact.RampDirection."""

    def __init__(self, d, k):
        self.direction, self.multiplier, self.mode, self.hinges = d, k, "rocking", (0, 5, 10, 15)
        self.sliding_joints = ()

    def to_dict(self):
        return {"direction": self.direction, "multiplier": self.multiplier,
                "hinges": list(self.hinges)}


class _Ramp:
    def __init__(self, kl, kr):
        self.l, self.r = _RD("l", kl), _RD("r", kr)


def _fake_engine(monkeypatch, first, refined):
    """Monkeypatch the engine: ramp -> ``first`` (k_l, k_r); refined -> ``refined[d]``."""
    import archrock.contact as contact

    calls = []
    monkeypatch.setattr(contact, "import_pymunk", lambda: None)
    monkeypatch.setattr(contact, "ramp", lambda arch, settings, progress=None, limit=None:
                        _Ramp(*first))

    def ramp_direction(arch, d, settings, **kw):
        calls.append((d, settings.tolerance, settings.steps_per_T))
        return _RD(d, refined[d])

    monkeypatch.setattr(contact, "ramp_direction", ramp_direction)
    return calls


def test_decision_engine_not_converged(monkeypatch, opp):
    """Engine 31% / 19.5% below the limit analysis, moving by more than 2% when refined: not
    converged, the limit analysis governs, the finding quotes both engine values and names the
    asymmetry on a mirror-symmetric arch."""
    arch, lim = opp
    calls = _fake_engine(monkeypatch, (0.2553, 0.2979), {"l": 0.3161, "r": 0.3482})
    g = governing_capacity(arch, 0.8, engine=True, limit=lim)
    # refined: a ten times tighter solver and twice the steps
    assert calls == [("l", pytest.approx(1e-7), 800.0), ("r", pytest.approx(1e-7), 800.0)]
    assert g.governing.analysis == NO_SLIDING
    assert g.governing.value == pytest.approx(0.370010, abs=5e-7)
    eng = g.analysis(ENGINE)
    assert eng.holds == {"l": False, "r": False} and "not converged" in eng.why["l"]
    text = " ".join(g.findings)
    assert "0.2553" in text and "0.3161" in text and "not converged" in text
    assert "mirror-symmetric" in text
    assert g.to_dict()["findings"] == list(g.findings)


def test_decision_engine_converged_and_lower_governs(monkeypatch, opp):
    """Engine 10% below and stable when refined: the models disagree and the engine's lower
    value governs (non-associative friction)."""
    arch, lim = opp
    _fake_engine(monkeypatch, (0.333, 0.333), {"l": 0.335, "r": 0.334})
    g = governing_capacity(arch, 0.8, engine=True, limit=lim)
    assert g.governing.analysis.startswith(ENGINE)
    assert g.governing.value == pytest.approx(0.333, abs=1e-12)
    assert g.governing.direction == "both"
    assert "engine's value governs" in " ".join(g.findings)


def test_decision_engine_agrees_limit_quoted(monkeypatch, opp):
    """Within 2%: no refined run, no finding, the exact limit value is quoted."""
    arch, lim = opp
    calls = _fake_engine(monkeypatch, (0.3687, 0.3687), {"l": 1.0, "r": 1.0})
    g = governing_capacity(arch, 0.8, engine=True, limit=lim)
    assert calls == [] and g.findings == ()
    assert g.governing.analysis == NO_SLIDING
    assert g.analysis(ENGINE).holds == {"l": True, "r": True}


def test_engine_with_sliding_excluded_runs_high_friction(monkeypatch, opp):
    """friction None: the engine runs at max(0.8, 2 x 0.4951) = 0.990 and says so."""
    arch, lim = opp
    seen = {}
    import archrock.contact as contact

    monkeypatch.setattr(contact, "import_pymunk", lambda: None)

    def ramp(arch, settings, progress=None, limit=None):
        seen["mu"] = settings.friction
        return _Ramp(0.37, 0.37)

    monkeypatch.setattr(contact, "ramp", ramp)
    g = governing_capacity(arch, None, engine=True, limit=lim)
    assert seen["mu"] == pytest.approx(2 * 0.49513, abs=1e-4)
    assert "sliding excluded by the user" in g.analysis(ENGINE).details["friction_note"]


def test_engine_runs_without_pymunk(monkeypatch, opp):
    """archrock's own engine needs no pymunk: with pymunk missing the engine's ramp is an
    analysis, agreeing with k = 0.3700 within 0.5% both ways."""
    import archrock.contact.engine as engine

    def missing():
        raise ImportError("no pymunk")

    monkeypatch.setattr(engine, "import_pymunk", missing)
    arch, lim = opp
    g = governing_capacity(arch, 0.8, engine=True, limit=lim)
    assert ENGINE not in dict(g.left_out)
    eng = g.analysis(ENGINE)
    for d in ("l", "r"):
        ramp = eng.details["ramp"][d]
        assert abs(ramp["multiplier"] / lim.k_l - 1) < 0.005
    assert eng.details["refined"] == {}


@pytest.mark.slow
def test_flat_arch_engine_agrees_with_the_limit_analysis():
    """The flat bridge arch on which pymunk's engine was 31% / 19.5% below k = 1.9045 (issue 31):
    archrock's engine agrees within 0.5% both ways, nothing is refined, and the exact limit value
    governs."""
    arch = family_arch("circular", 10, 1.5, 0.5, 15)
    g = governing_capacity(arch, 0.8, engine=True)
    assert g.governing.value == pytest.approx(1.9045, abs=5e-5)
    assert g.governing.analysis == NO_SLIDING
    eng = g.analysis(ENGINE)
    for d in ("l", "r"):
        assert abs(eng.details["ramp"][d]["multiplier"] / 1.9045 - 1) < 0.005
    assert eng.details["refined"] == {}
    assert not any("not converged" in f for f in g.findings)
