"""Arcades in the contact engine (archrock.contact.arcade): the ramp against the graph LP, and
the response to a pulse."""

import numpy as np
import pytest

pytest.importorskip("pymunk")

from archrock.contact import ContactArch, EngineSettings  # noqa: E402
from archrock.contact.arcade import (ContactArcade, arcade_ramp,  # noqa: E402
                                     arcade_ramp_direction, arcade_respond)
from archrock.errors import ArchInputError  # noqa: E402
from archrock.geometry import nominal_arch, with_piers  # noqa: E402
from archrock.geometry.arcade import GROUND, Arcade, Block, Contact, arcade  # noqa: E402
from archrock.groundmotion import PulseSpec  # noqa: E402
from archrock.statics.graph import graph_limit  # noqa: E402


def _frame(b=0.3, h=1.2, depth=0.3, span=6.0, columns=2):
    xs = tuple(np.linspace(0.0, span, columns))
    blocks = [Block([(x - b, 0), (x + b, 0), (x + b, 2 * h), (x - b, 2 * h)], "pier",
                    f"column {i + 1}") for i, x in enumerate(xs)]
    blocks.append(Block([(-b, 2 * h), (span + b, 2 * h), (span + b, 2 * h + depth),
                         (-b, 2 * h + depth)], "beam", "beam"))
    contacts = [Contact(GROUND, i, [(x - b, 0), (x + b, 0)], f"column {i + 1} foot",
                        ("left", "right")) for i, x in enumerate(xs)]
    contacts += [Contact(i, columns, [(x - b, 2 * h), (x + b, 2 * h)], f"column {i + 1} top",
                         ("left", "right")) for i, x in enumerate(xs)]
    return Arcade(tuple(blocks), tuple(contacts), 2000.0, "frame")


@pytest.fixture(scope="module")
def semicircle():
    return nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9)


def test_bodies_are_the_chain_engine_s(semicircle):
    """A one-span arcade's bodies carry the masses and inertias the chain's engine gives its
    voussoirs and piers, and stand at rest under gravity."""
    chain = with_piers(semicircle, 4.0, 2.0)
    ca = ContactArcade(arcade([semicircle], 4.0, 2.0))
    cc = ContactArch(chain)
    # to rounding: the arcade and the chain compute their blocks' properties by their own code
    np.testing.assert_allclose(ca.masses, cc.masses, rtol=1e-12)
    np.testing.assert_allclose(ca.inertias, cc.inertias, rtol=1e-12)
    assert len(ca.ground_outlines) == 2
    ca.settle()
    ca.step(0.0, 200)
    pos, ang, vel, rate = ca.state()
    assert np.abs(ang - ca.ref_ang).max() < 1e-4
    assert np.abs(ca.contact_rotations(ang) - ca.contact_rotations(ca.ref_ang)).max() < 1e-4


def test_rocking_frame_ramp_and_hinges():
    """The frame activates at b/h = 0.25 in the engine (within 2%), on the LP's four hinges."""
    arc = _frame()
    g = graph_limit(arc, "l")
    r = arcade_ramp_direction(arc, "l", lambda_max=0.5, tol=0.01, hold=2.0)
    assert r.multiplier == pytest.approx(0.25, rel=0.02)
    assert sorted(r.hinges) == sorted((h.contact, h.end) for h in g.hinges)
    assert r.mode == "rocking" and r.lower < r.upper
    with pytest.raises(ArchInputError, match="direction: 'x'"):
        arcade_ramp_direction(arc, "x")
    with pytest.raises(ArchInputError, match="lambda_max"):
        arcade_ramp_direction(arc, "l", lambda_max=0.0)


def test_column_array_ramp():
    """Four columns under one beam activate together at b/h in the engine (within 2%), on the
    LP's eight hinges."""
    arc = _frame(b=0.25, h=1.0, span=9.0, columns=4)
    g = graph_limit(arc, "r")
    assert g.k == pytest.approx(0.25, abs=1e-9)
    r = arcade_ramp_direction(arc, "r", lambda_max=0.5, tol=0.01, hold=2.0)
    assert r.multiplier == pytest.approx(0.25, rel=0.02)
    assert sorted(r.hinges) == sorted((h.contact, h.end) for h in g.hinges)


def test_frame_response_below_and_above_activation():
    """A rectangular pulse below b/h leaves the frame at rest; a long one well above it
    overturns it, the columns turning under a beam that does not."""
    arc = _frame()
    rest = arcade_respond(arc, PulseSpec("rectangular", -0.2, 0.5).build(), t_end=1.0,
                          t_free=2.0)
    assert rest.status == "rest" and rest.peak_rotation < 1e-3 and not rest.moved
    gone = arcade_respond(arc, PulseSpec("rectangular", -0.8, 2.0).build(), t_end=1.0)
    assert gone.collapsed and gone.t_collapse is not None and gone.t_collapse < 2.5
    # the columns turn, the beam rides on them without turning (the frame's mechanism)
    assert set(gone.moved) == {0, 1}
    assert np.nanmax(np.abs(gone.rotations[:, 2])) < 1e-3
    d = gone.to_dict()
    assert d["collapsed"] and d["run"]["motion"]


@pytest.mark.slow
@pytest.mark.parametrize("spans, k", [(2, 0.140874), (3, 0.139911)])
def test_two_and_three_span_ramp_against_the_lp(spans, k, semicircle):
    """The engine's activation of the sway mechanism of two- and three-span arcades on 8 m
    piers (end piers 2.5 m, inner 1.8 m): within 2% of the graph LP's k (measured 0.2-0.5%
    below), the same hinges, both directions."""
    arc = arcade([semicircle] * spans, 8.0, [2.5] + [1.8] * (spans - 1) + [2.5])
    gl, gr = graph_limit(arc, "l"), graph_limit(arc, "r")
    assert gl.k == pytest.approx(k, abs=5e-7)
    res = arcade_ramp(arc, EngineSettings(), k_l=gl.k, k_r=gr.k)
    for d, g in (("l", gl), ("r", gr)):
        r = getattr(res, d)
        assert r.multiplier == pytest.approx(g.k, rel=0.02)
        assert sorted(r.hinges) == sorted((h.contact, h.end) for h in g.hinges)
        assert r.mode == "rocking"


@pytest.mark.slow
def test_arcade_under_the_paper_s_pulse(semicircle):
    """The three-span arcade under Oppenheim's pulse (t_p = 0.2 s): at rest after 0.1 g, down
    after 0.3 g."""
    arc = arcade([semicircle] * 3, 8.0, [2.5, 1.8, 1.8, 2.5])
    low = arcade_respond(arc, PulseSpec("oppenheim", -0.1, 0.2).build(), t_end=1.0)
    assert low.status == "rest"
    high = arcade_respond(arc, PulseSpec("oppenheim", -0.3, 0.2).build(), t_end=1.0)
    assert high.collapsed


@pytest.mark.slow
def test_mixed_arcade_reads_the_mechanism_not_a_settling_start(semicircle):
    """A semicircle beside a pointed arch on unequal piers, loads toward -x: the semicircle
    alone between its piers governs (k = 0.174779).  A hold just at the engine's activation
    starts and settles back; the hinges come from the lowest hold whose motion grew: the LP's
    (measured: activation 1.6% below k)."""
    from archrock.geometry import family_arch

    arc = arcade([semicircle, family_arch("pointed", 8, 6, 0.7, 8)], [6.0, 7.0, 5.0],
                 [2.5, 2.0, 2.0])
    g = graph_limit(arc, "r")
    assert g.k == pytest.approx(0.174779, abs=5e-7)
    r = arcade_ramp_direction(arc, "r", lambda_max=2.0)
    assert r.multiplier == pytest.approx(g.k, rel=0.02)
    assert sorted(r.hinges) == sorted((h.contact, h.end) for h in g.hinges)
