"""Friction together with a finite compressive strength in the governing capacity: Heyman's
friction analysis assumes no crushing, so with f_c the friction analysis is the graph of
blocks' (friction rows and the stress-block bracket in one program)."""

from __future__ import annotations

import pytest

from archrock.geometry import family_arch
from archrock.geometry.arcade import arcade_from_chain
from archrock.statics.friction import friction_analysis
from archrock.statics.graph import graph_limit
from archrock.statics.limit import limit_analysis
from archrock.studies.governing import NO_SLIDING, governing_capacity


@pytest.fixture(scope="module")
def flat():
    """The issue's flat bridge arch: span 10 m, rise 1.5 m, t 0.5 m, 15 voussoirs."""
    return family_arch("circular", 10.0, 1.5, 0.5, 15)


def test_graph_friction_is_heymans_friction_at_infinite_strength(flat):
    """The second method the governing capacity uses with f_c gives Heyman's friction
    analysis where f_c is infinite (two programs, one answer)."""
    fa = friction_analysis(flat, 0.3)
    g = graph_limit(arcade_from_chain(flat), "l", friction=0.3)
    assert g.k == pytest.approx(fa.l.multiplier, rel=1e-9)


def test_low_friction_and_crushing_together_govern_below_either_alone(flat):
    arch = flat.with_fc(2.0)
    k_crush = limit_analysis(arch).k
    k_fric = friction_analysis(flat, 0.3).k
    gc = governing_capacity(arch, 0.3)
    gov = gc.governing
    assert gov.analysis.startswith("limit analysis with friction")
    assert "crushing at f_c = 2 MPa" in gov.hypotheses
    # both mechanisms interact: below the crushing-only 1.6100 and the sliding-only 1.6533
    assert gov.value < k_crush - 0.1 and gov.value < k_fric - 0.1
    assert gov.value == pytest.approx(1.4224, abs=1e-3)
    # the crushing-only answer does not hold: its joints slide first
    ns = gc.analysis(NO_SLIDING)
    assert not ns.holds["l"] and "slide first" in ns.why["l"]


def test_enough_friction_leaves_the_crushing_answer_governing(flat):
    arch = flat.with_fc(2.0)
    gov = governing_capacity(arch, 0.8).governing
    assert gov.analysis == NO_SLIDING
    assert gov.value == pytest.approx(limit_analysis(arch).k, rel=1e-9)


@pytest.mark.parametrize("which", ["flat", "oppenheim"])
def test_friction_needed_on_the_crushing_thrust_is_the_graph_programs_threshold(flat, which):
    """Two methods, one threshold: the largest |T|/N on the finite-strength collapse's thrust
    line (what assess reports as the friction needed) is where the graph program with friction
    and crushing starts to carry less than crushing alone."""
    from archrock.geometry import oppenheim_arch
    from archrock.statics.friction import thrust_friction
    from archrock.studies.governing import friction_with_crushing

    arch = (flat if which == "flat" else oppenheim_arch()).with_fc(2.0)
    lim = limit_analysis(arch)
    need = thrust_friction(arch, {"l": lim.thrust_l, "r": lim.thrust_r})["l"]
    assert 0.3 < need < 0.8  # 0.5931 flat, 0.4536 Oppenheim's
    below = friction_with_crushing(arch, 0.98 * need).k_l
    above = friction_with_crushing(arch, 1.02 * need).k_l
    assert below < lim.k_l * (1 - 1e-3)
    assert above == pytest.approx(lim.k_l, rel=1e-6)


def test_assess_friction_section_with_fc_is_friction_and_crushing_together(flat):
    from archrock.studies.assessment import AssessConfig
    from archrock.studies.assessment_context import Context
    from archrock.studies.assessment_statics import section_friction

    arch = flat.with_fc(2.0)
    sec = section_friction(Context(arch, AssessConfig(friction=0.3), engine=False))
    assert sec.data["k_with_mu"]["l"] == pytest.approx(1.4224, abs=1e-3)
    assert sec.data["sliding_governs"] == {"l": True, "r": True}
    assert sec.data["friction_needed_l"] == pytest.approx(0.5931, abs=1e-3)
