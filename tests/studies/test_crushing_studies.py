"""Every study takes f_c (issue 34): the ensemble, the defect map, the code check, the Sobol
indices and assess's crushing section each change with a finite strength, and each is what it
was with the strength infinite (the arches' f_c None)."""

import numpy as np
import pytest

from archrock.geometry import oppenheim_arch
from archrock.geometry.sampling import Spreads
from archrock.statics.limit import limit_analysis
from archrock.studies.assessment import assess
from archrock.studies.assessment_crushing import hinge_zones, section_crushing
from archrock.studies.assessment_context import AssessConfig, Context
from archrock.studies.codecheck import code_check
from archrock.studies.defectmap import defect_map
from archrock.studies.ensemble import EnsembleConfig
from archrock.studies.ensemble.compute import run_batch


def _ensemble(nominal, spreads=Spreads(0.1, 0.1, 0.05)):
    cfg = EnsembleConfig.from_arch(nominal, samples=8, seed=1, spreads=spreads, batch_size=8)
    return run_batch(cfg, 0, parallel=False)[0]


def test_ensemble_arches_carry_fc_and_lose_capacity():
    plain = _ensemble(oppenheim_arch())
    again = _ensemble(oppenheim_arch())
    weak = _ensemble(oppenheim_arch().with_fc(3.0))
    spread = _ensemble(oppenheim_arch().with_fc(3.0), Spreads(0.1, 0.1, 0.05, fc=0.5))
    assert np.array_equal(plain["k_l"].to_numpy(), again["k_l"].to_numpy())  # None: as before
    assert (weak["k_l"] < plain["k_l"] - 1e-3).all() and (weak["k_r"] < plain["k_r"]).all()
    # the strength's spread moves k around the fixed strength's
    assert not np.allclose(spread["k_l"], weak["k_l"], rtol=1e-6, atol=0)


def test_defect_map_keeps_fc():
    plain = defect_map(oppenheim_arch(), "thickness", 0.7, indices=[2])
    weak = defect_map(oppenheim_arch().with_fc(3.0), "thickness", 0.7, indices=[2])
    assert weak.k_l0 == pytest.approx(limit_analysis(oppenheim_arch().with_fc(3.0)).k_l,
                                      rel=1e-9)
    assert weak.k_l0 < plain.k_l0 - 1e-3 and weak.k_l[0] < plain.k_l[0] - 1e-3


def test_code_check_activates_at_the_finite_strength_multiplier():
    plain = code_check(oppenheim_arch())
    weak_arch = oppenheim_arch().with_fc(3.0)
    weak = code_check(weak_arch)
    k = limit_analysis(weak_arch).k_l
    assert weak.directions[0].alpha_0 == pytest.approx(k, rel=1e-9)
    assert plain.directions[0].alpha_0 == pytest.approx(limit_analysis(oppenheim_arch()).k_l,
                                                        rel=1e-9)
    assert weak.directions[0].a0_star < plain.directions[0].a0_star


def test_crushing_section_only_with_fc():
    cfg = AssessConfig()
    assert section_crushing(Context(oppenheim_arch(), cfg)) is None
    arch = oppenheim_arch().with_fc(2.0)
    sec = section_crushing(Context(arch, cfg))
    d = sec.data
    assert d["fc"] == pytest.approx(2.0, rel=0, abs=0)
    assert d["k_l"] < d["heyman_k_l"] and d["governs"] == "finite strength"
    zl = hinge_zones(arch, limit_analysis(arch), "l")
    assert len(zl) == 4 and all(0 < z["ratio"] < 1 for z in zl)
    # the stress block carries N = a f_c: a zone of a [m] at 2 MPa carries 2e6 a N/m
    assert all(z["N"] == pytest.approx(2e6 * z["zone"], rel=1e-12) for z in zl)
    low, high = d["k_bounds_l"]
    assert low <= d["k_l"] * (1 + 1e-9) and d["k_l"] <= high * (1 + 1e-9)


def test_assess_report_has_the_crushing_section_with_fc():
    keys = [s.key for s in assess(oppenheim_arch().with_fc(2.0),
                                  sections=[section_crushing]).sections]
    assert keys == ["crushing"]
    assert [s.key for s in assess(oppenheim_arch(), sections=[section_crushing]).sections] == []


def test_curves_and_fragility_arches_carry_fc():
    """The arches of curves, fragility and the IDA (dynamics.population.prepare_many) are the
    sampler's, each with its f_c, rocking about the inset hinges."""
    from archrock.dynamics.population import prepare_many
    from archrock.geometry.sampling import ArchSampler

    plain = prepare_many(ArchSampler(oppenheim_arch(), seed=2), 3)
    weak = prepare_many(ArchSampler(oppenheim_arch().with_fc(3.0), seed=2), 3)
    for p, w in zip(plain, weak):
        assert w.arch.fc == pytest.approx(3.0, rel=0, abs=0) and p.arch.fc is None
        assert w.k_l < p.k_l - 1e-3
        assert -w.mech_l.static_multiplier() == pytest.approx(w.k_l, rel=1e-9)


def test_the_engine_chosen_for_an_arch_of_finite_strength_says_it_does_not_crush():
    from archrock.studies.enginestudy import choose_dynamics

    weak = choose_dynamics(oppenheim_arch().with_fc(3.0), "engine")
    plain = choose_dynamics(oppenheim_arch(), "engine")
    assert "f_c = 3 MPa is not in its answer" in weak.reason
    assert "crush" not in plain.reason
    assert "crush" not in choose_dynamics(oppenheim_arch().with_fc(3.0)).reason  # four-link
