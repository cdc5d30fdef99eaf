"""Limit analysis of brick arches of several rings on the graph of blocks: the ring interfaces'
own Coulomb friction and cohesion in the static program, ring separation in the mechanism."""

from __future__ import annotations

import pytest

from archrock.geometry import nominal_arch
from archrock.geometry.arcade import arcade_from_chain
from archrock.geometry.rings import interface_contacts, ringed_arch
from archrock.statics.graph import graph_limit

R, T, BRICK = 2.5, 0.43, 0.5  # a semicircle of span 5 m, two rings of 0.215 m, 16 bricks a ring


@pytest.fixture(scope="module")
def monolithic():
    """k of the same arch in one ring of 16 voussoirs (today's graph answer)."""
    arch = nominal_arch(radius=R, embrace_deg=180.0, thickness=T, voussoirs=16)
    return graph_limit(arcade_from_chain(arch), "l").k


def _separation(arc, g) -> int:
    faces = set(interface_contacts(arc))
    m = g.mechanism
    return len(faces & (set(m.lift_off) | set(m.sliding) | {h.contact for h in m.hinges}))


def test_one_ring_is_todays_answer(monolithic):
    g = graph_limit(ringed_arch(R, T, rings=1, brick=BRICK), "l")
    assert abs(g.k - monolithic) <= 1e-12
    assert abs(g.k - 0.2101101542) < 1e-9
    assert len(g.hinges) == 4


def test_bonded_rings_near_the_monolithic_arch(monolithic):
    # joints through the depth, interfaces that never slide: only the rings' separation (no
    # tension across the interface) is left, and it costs 7.9 %
    aligned = graph_limit(ringed_arch(R, T, rings=2, brick=BRICK, friction=None,
                                      stagger=False), "l")
    assert aligned.k == pytest.approx(0.19349, abs=1e-5)
    assert 0.9 * monolithic < aligned.k < monolithic
    # bonded brickwork with a high friction: within 4 % of the monolithic arch (the staggered
    # joints interlock a little: +3.7 %)
    bonded = graph_limit(ringed_arch(R, T, rings=2, brick=BRICK, friction=2.0), "l")
    assert bonded.k == pytest.approx(0.217931, abs=1e-5)
    assert abs(bonded.k / monolithic - 1) < 0.04


def test_headers_every_two_bricks_are_the_monolithic_arch(monolithic):
    # every joint of the one-ring arch then runs through the depth, each pair of rings' bricks
    # between two of them tied by a header: the one-ring arch, to rounding
    g = graph_limit(ringed_arch(R, T, rings=2, brick=BRICK, headers=2), "l")
    assert abs(g.k - monolithic) < 1e-12
    # fewer headers: within 0.4 % (every 4 bricks), then the rings part between them
    ks = [graph_limit(ringed_arch(R, T, rings=2, brick=BRICK, headers=h), "l").k
          for h in (4, 8)]
    assert abs(ks[0] / monolithic - 1) < 0.005
    assert ks[1] < ks[0]
    assert ks[1] > graph_limit(ringed_arch(R, T, rings=2, brick=BRICK), "l").k


def test_lower_friction_lower_k_and_the_rings_separate(monolithic):
    ks = []
    for mu in (2.0, 0.8, 0.5):
        a = ringed_arch(R, T, rings=2, brick=BRICK, friction=mu)
        g = graph_limit(a, "l")
        assert abs(g.k_virtual_work - g.k) < 1e-9
        assert _separation(a, g) > 0
        ks.append(g.k)
    assert ks[0] > ks[1] > ks[2]
    assert ks[1] == pytest.approx(0.174130, abs=1e-5)  # mu = 0.8: 17 % below one ring
    assert ks[1] < 0.85 * monolithic
    assert set(g.mechanism.sliding) & set(interface_contacts(a))  # mu = 0.5: they slide


def test_symmetric_ringed_arch_same_both_ways():
    a = ringed_arch(R, T, rings=2, brick=BRICK, friction=0.6)
    kl, kr = graph_limit(a, "l").k, graph_limit(a, "r").k
    assert abs(kl - kr) < 1e-9
    assert abs(graph_limit(a.mirrored(), "r").k - kl) < 1e-9


def test_cohesion_raises_k_and_its_work_is_counted():
    ks = []
    for c in (0.0, 1e3, 5e3):
        g = graph_limit(ringed_arch(R, T, rings=2, brick=BRICK, friction=0.5, cohesion=c), "l")
        assert abs(g.k_virtual_work - g.k) < 1e-7
        ks.append(g.k)
    assert ks[0] < ks[1] < ks[2]
    assert "cohesion up to 5 kPa" in g.method


def test_radial_joints_take_the_analysis_friction():
    a = ringed_arch(R, T, rings=2, brick=BRICK, friction=0.8)
    base = graph_limit(a, "l")
    slip = graph_limit(a, "l", friction=0.5)  # now the radial joints slide too
    assert slip.k < base.k
    assert "without its own" in slip.method
