"""Finite compressive strength on the graph of blocks (archrock.statics.graphcrush): the pier's
closed form, Heyman's answers unchanged at infinite strength, weaker piers, the bracket and the
stress blocks' centres."""

import numpy as np
import pytest

from archrock.errors import ArchInputError, CannotStandError
from archrock.geometry import nominal_arch
from archrock.geometry.arcade import GROUND, Arcade, Block, Contact, arcade, arcade_from_chain
from archrock.statics.graph import graph_limit, graph_multiplier
from archrock.statics.graphcrush import BRACKET_RTOL
from archrock.units import G

B, H, RHO = 1.0, 4.0, 2000.0  # the pier: width [m], height [m], density [kg/m^3]
W = RHO * B * H * G  # its weight [N per m of depth]


def pier(courses: int, fc) -> Arcade:
    """A rectangular pier of B x H in ``courses`` equal courses on the ground."""
    lv = np.linspace(0.0, H, courses + 1)
    blocks = tuple(Block(np.array([[0, lv[i]], [B, lv[i]], [B, lv[i + 1]], [0, lv[i + 1]]]),
                         "pier", f"course {i + 1}") for i in range(courses))
    contacts = tuple(Contact(GROUND if i == 0 else i - 1, i, np.array([[0, lv[i]], [B, lv[i]]]),
                             f"bed {i}", ("left face", "right face")) for i in range(courses))
    return Arcade(blocks, contacts, RHO, fc=fc)


@pytest.fixture(scope="module")
def semicircle():
    return nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9)


@pytest.fixture(scope="module")
def oppenheim_geometry():
    """Oppenheim's arch alone (conftest's ``oppenheim`` also builds its dynamics)."""
    from archrock.geometry import oppenheim_arch

    return oppenheim_arch()


@pytest.mark.parametrize("courses", [1, 4])
@pytest.mark.parametrize("fc", [0.1, 0.2, 0.5, 2.0])
def test_pier_closed_form(courses, fc):
    """A pier of width b, height h, weight W overturns about the centre of the stress block at
    its foot, W / (2 f_c) in from the edge: lambda = (b - W / f_c) / h, to 1e-9 (the static
    optimum, both bounds and the mechanism's virtual work); the foot governs a coursed pier."""
    exact = (B - W / (fc * 1e6)) / H
    for d, end in (("l", 1), ("r", 0)):
        g = graph_limit(pier(courses, fc), d)
        assert g.k == pytest.approx(exact, abs=1e-9)
        assert g.k_bounds[0] == pytest.approx(exact, abs=1e-9)
        assert g.k_bounds[1] == pytest.approx(exact, abs=1e-9)
        assert g.k_virtual_work == pytest.approx(exact, abs=1e-9)
        (h,) = g.hinges
        assert (h.contact, h.end) == (0, end)
        # the hinge at the stress block's centre, W / (2 f_c) in from the turning edge
        inset = W / (2 * fc * 1e6)
        assert h.point[0] == pytest.approx(B - inset if end else inset, abs=1e-9)
        assert g.zones[0] == pytest.approx(W / (fc * 1e6), rel=1e-9)


def test_pier_crushed_by_its_weight():
    """W / f_c wider than the pier (a 10 m pier of 0.05 m at 0.1 MPa needs 0.098 m of stress
    block): it cannot stand; at half the height (0.049 m) it stands, barely."""
    thin = Arcade((Block(np.array([[0, 0], [0.05, 0], [0.05, 10.0], [0, 10.0]]), "pier"),),
                  (Contact(GROUND, 0, np.array([[0, 0], [0.05, 0]])),), RHO, fc=0.1)
    with pytest.raises(CannotStandError, match="cannot stand"):
        graph_limit(thin, "l")
    short = Arcade((Block(np.array([[0, 0], [0.05, 0], [0.05, 5.0], [0, 5.0]]), "pier"),),
                   (Contact(GROUND, 0, np.array([[0, 0], [0.05, 0]])),), RHO, fc=0.1)
    assert graph_limit(short, "l").k == pytest.approx((0.05 - 0.04905) / 5.0, abs=1e-9)


def _same(a, b):
    assert a.k == b.k and a.k_virtual_work == b.k_virtual_work
    assert np.array_equal(a.forces, b.forces)
    assert np.array_equal(a.mechanism.velocities, b.mechanism.velocities)
    assert a.hinges == b.hinges and a.method == b.method


def test_infinite_strength_is_heymans_bit_for_bit(semicircle):
    """fc None (absent, or set and taken back) gives today's graph LP: the same numbers to the
    bit, no bracket, no zones, and the documents without an "fc"."""
    base = arcade([semicircle, semicircle], 4.0, 2.0, courses=2)
    back = base.with_fc(5.0).with_fc(None)
    assert "fc" not in base.to_dict() and "fc" not in back.to_dict()
    for d in "lr":
        g = graph_limit(base, d)
        assert g.k_bounds is None and g.zones is None
        assert "k_bounds" not in g.to_dict()
        _same(g, graph_limit(back, d))
        _same(graph_limit(base, d, friction=0.6), graph_limit(back, d, friction=0.6))
    # the reference semicircle on 4 x 2 m piers (docs/piers.md)
    assert graph_limit(base, "l").k == pytest.approx(0.168899, abs=5e-7)


def test_weaker_piers(semicircle):
    """The semicircle on 4 x 2 m piers: voussoirs of 10 MPa, piers of 1 MPa carry less than
    both at 10 MPa, which carry less than Heyman's arch; the weak pier's foot is a hinge with
    a stress block, the bracket within 1e-6 and the mechanism's virtual work k to 1e-9."""
    base = arcade([semicircle], 4.0, 2.0)
    heyman = graph_limit(base, "l").k
    strong = graph_limit(base.with_fc(10.0), "l")
    weak = graph_limit(base.with_fc({"voussoir": 10.0, "pier": 1.0}), "l")
    assert weak.k < strong.k - 1e-3 < heyman - 2e-3
    for g in (strong, weak):
        lo, hi = g.k_bounds
        assert lo == g.k and hi - lo <= BRACKET_RTOL * abs(hi)
        assert g.k_virtual_work == pytest.approx(g.k, abs=1e-9)
        assert g.mechanism.dof == 1
    foot = next(h for h in weak.hinges if "pier 2 foot" in h.place)
    arc = base.with_fc({"voussoir": 10.0, "pier": 1.0})
    assert arc.contact_fc[foot.contact] == 1.0
    assert weak.zones[foot.contact] > 0.1  # a 1 MPa pier's foot: some 0.2 m of stress block


def test_the_static_state_meets_the_stress_block_condition(semicircle):
    """At k (the lower bound) every contact's thrust lies at least N / (2 f_c) from both its
    ends: the exact condition, not its linearisation."""
    arc = arcade([semicircle, semicircle], 4.0, 2.0).with_fc({"voussoir": 2.0, "pier": 0.5})
    g = graph_limit(arc, "r")
    scale = 1e-9 * float(np.sum(arc.masses)) * G * arc.extent  # the program's units, 1e-9
    for c, ct in enumerate(arc.contacts):
        n0, n1 = g.forces[c, :2]
        n = n0 + n1
        length = float(np.hypot(*(ct.points[1] - ct.points[0])))
        half = n * n / (2 * arc.contact_fc[c] * 1e6)
        assert half <= length * min(n0, n1) + scale


def test_strength_lowers_k_and_the_mirror_agrees(oppenheim_geometry):
    """Oppenheim's arch from the ground: k falls as f_c falls, and the mirror image's k_r is
    k_l; the multiplier alone (graph_multiplier) is the bracket's lower bound."""
    base = arcade_from_chain(oppenheim_geometry)
    ks = [graph_limit(base.with_fc(fc), "l").k for fc in (10.0, 5.0, 2.0, 1.0)]
    assert np.all(np.diff(ks) < 0) and ks[0] < 0.370010
    arc = base.with_fc(2.0)
    assert graph_limit(arc.mirrored(), "r").k == pytest.approx(ks[2], abs=1e-6)
    assert graph_multiplier(arc, "l") == pytest.approx(ks[2], abs=1e-12)


def test_chain_strength_reaches_the_arcade(semicircle):
    """arcade_from_chain and arcade() take the arches' own fc; arches of different fc need an
    explicit one."""
    assert arcade_from_chain(semicircle.with_fc(3.0)).fc == {"voussoir": 3.0}
    assert arcade([semicircle.with_fc(3.0)], 4.0, 2.0).fc == {"voussoir": 3.0, "pier": 3.0}
    with pytest.raises(ArchInputError, match="arches: compressive strengths"):
        arcade([semicircle.with_fc(3.0), semicircle], 4.0, 2.0)
    assert arcade([semicircle.with_fc(3.0), semicircle], 4.0, 2.0, fc=4.0).fc["pier"] == 4.0


def test_friction_together_with_crushing(semicircle):
    """Coulomb rows and stress blocks in one program: a pier slides at k = mu where mu is below
    its crushing lambda and rocks at lambda above it; the two-span arcade at mu = 0.45 slides at
    a springing and carries less with f_c = 1 MPa than without, its mechanism's virtual work
    k to 1e-9."""
    lam = (B - W / 0.5e6) / H
    slid = graph_limit(pier(2, 0.5), "l", friction=0.05)
    assert slid.k == pytest.approx(0.05, abs=1e-9) and slid.mechanism.sliding
    rocks = graph_limit(pier(2, 0.5), "l", friction=0.6)
    assert rocks.k == pytest.approx(lam, abs=1e-9) and not rocks.mechanism.sliding
    arc = arcade([semicircle, semicircle], 4.0, 2.0, courses=2)
    heyman = graph_limit(arc, "l", friction=0.45)
    g = graph_limit(arc.with_fc(1.0), "l", friction=0.45)
    assert g.k < heyman.k - 0.01
    springings = {c for c, ct in enumerate(arc.contacts) if "springing" in ct.label}
    assert set(heyman.mechanism.sliding) == {23} and set(g.mechanism.sliding) <= springings
    assert g.mechanism.sliding
    assert g.k_virtual_work == pytest.approx(g.k, abs=1e-9)
    assert g.k_bounds[1] - g.k_bounds[0] <= BRACKET_RTOL * g.k_bounds[1]


EDGE = {"intrados": 0, "extrados": 1}


@pytest.mark.parametrize("which, fc", [("oppenheim", 1.0), ("oppenheim", 2.0),
                                       ("oppenheim", 5.0), ("oppenheim", 10.0), ("flat", 1.0),
                                       ("flat", 2.0), ("flat", 5.0), ("flat", 10.0),
                                       ("piers", 1.0), ("piers", 10.0)])
def test_graph_equals_the_chain_with_crushing(which, fc, oppenheim_geometry, semicircle):
    """The same arch as a chain (statics.crushing, joint-line redundants, Newton at the
    optimum) and as a graph (this bracket on contact end forces): Oppenheim's arch, the flat
    bridge arch (span 10, rise 1.5, t 0.5, 15 voussoirs) and the semicircle on 4 x 2 m piers
    agree to 1e-8 with the same hinges, at f_c = 1 to 10 MPa."""
    from archrock.geometry import family_arch, with_piers
    from archrock.statics.limit import limit_analysis

    arch = {"oppenheim": lambda: oppenheim_geometry,
            "flat": lambda: family_arch("circular", 10, 1.5, 0.5, 15),
            "piers": lambda: with_piers(semicircle, 4.0, 2.0)}[which]().with_fc(fc)
    lim = limit_analysis(arch)
    g = graph_limit(arcade_from_chain(arch), "l")
    assert g.k == pytest.approx(lim.k_l, abs=1e-8)
    assert g.k_virtual_work == pytest.approx(g.k, abs=1e-9)
    assert sorted((h.contact, h.end) for h in g.hinges) == \
        sorted((h.joint, EDGE[h.edge]) for h in lim.mechanism("l").hinges)
