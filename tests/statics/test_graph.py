"""The static LP on a graph of blocks (archrock.statics.graph), against the chain's LP, closed
forms of rocking frames, mirror symmetry, and its own virtual work."""

import numpy as np
import pytest

from archrock.errors import ArchInputError, CannotStandError
from archrock.geometry import family_arch, nominal_arch, with_piers
from archrock.geometry.arcade import GROUND, Arcade, Block, Contact, arcade, arcade_from_chain
from archrock.statics.graph import graph_limit, graph_multiplier
from archrock.statics.limit import limit_analysis
from archrock.statics.lp import static_multiplier

EDGE = {"intrados": 0, "extrados": 1}


@pytest.fixture(scope="module")
def semicircle():
    return nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9)


@pytest.fixture(scope="module")
def pointed():
    return family_arch("pointed", 10, 7, 0.9, 10)


@pytest.mark.parametrize("which, courses", [("semicircle", 2), ("pointed", 1),
                                            ("semicircle", 1)])
def test_one_span_equals_the_chain_lp(which, courses, semicircle, pointed):
    """k and the hinges of a one-span arcade are the chain's (ArchOnPiers) to 1e-9: the static
    optimum, the kinematic governing mechanism, and the hinges read from the dual."""
    arch = semicircle if which == "semicircle" else pointed
    chain = with_piers(arch, 4.0, 2.0, courses=courses)
    lim = limit_analysis(chain)
    arc = arcade([arch], 4.0, 2.0, courses=courses)
    for d in "lr":
        g = graph_limit(arc, d)
        k_static, _ = static_multiplier(chain, d)
        assert g.k == pytest.approx(k_static, abs=1e-9)
        assert g.k == pytest.approx(lim.mechanism(d).multiplier, abs=1e-9)
        assert g.k_virtual_work == pytest.approx(g.k, abs=1e-9)
        assert g.mechanism.dof == 1
        assert sorted((h.contact, h.end) for h in g.hinges) == \
            sorted((h.joint, EDGE[h.edge]) for h in lim.mechanism(d).hinges)
    # the reference semicircle on 4 x 2 m piers (docs/piers.md): 0.168899, D at the far foot
    if which == "semicircle":
        g = graph_limit(arc, "l")
        assert g.k == pytest.approx(0.168899, abs=5e-7)
        assert g.hinges[-1].place == "pier 2 foot, outer face"


def test_rigid_ground_oppenheim(oppenheim):
    """Oppenheim's arch springing from the ground, as a graph: k = 0.370010 (the paper's)."""
    arc = arcade_from_chain(oppenheim.arch)
    for d in "lr":
        g = graph_limit(arc, d)
        assert g.k == pytest.approx(0.370010, abs=5e-7)
        assert g.k == pytest.approx(oppenheim.limit.mechanism(d).multiplier, abs=1e-9)
        assert g.k_virtual_work == pytest.approx(g.k, abs=1e-9)
        assert sorted((h.contact, h.end) for h in g.hinges) == \
            sorted((h.joint, EDGE[h.edge]) for h in oppenheim.limit.mechanism(d).hinges)


def _frame(b, h, depth, columns=2, span=6.0, density=2000.0, load=0.0):
    """Makris & Vassiliou's frame: ``columns`` columns 2b x 2h equally spaced over ``span``
    under one free beam of depth ``depth`` (a load [kg/m] at the beam's middle)."""
    xs = np.linspace(0.0, span, columns)
    blocks, contacts = [], []
    for i, x in enumerate(xs):
        blocks.append(Block([(x - b, 0), (x + b, 0), (x + b, 2 * h), (x - b, 2 * h)], "pier",
                            f"column {i + 1}"))
        contacts.append(Contact(GROUND, i, [(x - b, 0), (x + b, 0)], f"column {i + 1} foot",
                                ("left", "right")))
    top = 2 * h
    loads = ((load, (0.5 * span, top + depth)),) if load else ()
    blocks.append(Block([(xs[0] - b, top), (xs[-1] + b, top), (xs[-1] + b, top + depth),
                         (xs[0] - b, top + depth)], "beam", "beam", loads))
    for i, x in enumerate(xs):
        contacts.append(Contact(i, columns, [(x - b, top), (x + b, top)],
                                f"column {i + 1} top", ("left", "right")))
    return Arcade(tuple(blocks), tuple(contacts), density, "frame")


@pytest.mark.parametrize("b, h, depth, load", [(0.3, 1.2, 0.3, 0.0), (0.2, 2.5, 0.6, 0.0),
                                               (0.1, 1.2, 0.05, 0.0), (0.3, 1.2, 0.3, 5e4),
                                               (0.33, 1.0, 0.2, 0.0)])
def test_rocking_frame_closed_form(b, h, depth, load):
    """Two columns 2b x 2h under a free beam: k = tan(alpha) = b/h whatever the beam's mass
    (Makris & Vassiliou 2013), both directions, four hinges: each column on one foot corner and
    under the beam's opposite corner."""
    arc = _frame(b, h, depth, load=load)
    for d, foot, head in (("l", "right", "left"), ("r", "left", "right")):
        g = graph_limit(arc, d)
        assert g.k == pytest.approx(b / h, abs=1e-9)
        assert g.k_virtual_work == pytest.approx(b / h, abs=1e-9)
        assert sorted(h_.place for h_ in g.hinges) == sorted(
            [f"column 1 foot, {foot}", f"column 2 foot, {foot}", f"column 1 top, {head}",
             f"column 2 top, {head}"])
        assert g.mechanism.dof == 1 and not g.mechanism.lift_off and not g.mechanism.sliding
        # the beam translates: no rotation, and every column turns alike
        v = g.mechanism.velocities
        assert abs(v[2, 2]) < 1e-9 * np.abs(v).max()
        assert v[0, 2] == pytest.approx(v[1, 2], rel=1e-9)


@pytest.mark.parametrize("columns", [3, 5, 8])
def test_column_array_under_one_beam(columns):
    """N columns under one beam behave as the two-column frame: k = b/h, 2N hinges, 1 dof."""
    g = graph_limit(_frame(0.25, 1.5, 0.3, columns=columns, span=12.0), "l")
    assert g.k == pytest.approx(0.25 / 1.5, abs=1e-9)
    assert g.k_virtual_work == pytest.approx(g.k, abs=1e-9)
    assert len(g.hinges) == 2 * columns and g.mechanism.dof == 1


def test_frame_friction_slides_at_mu():
    """With Coulomb rows the frame slides on its feet at k = mu below b/h (docs/piers.md's
    hand check), and rocks again above it."""
    arc = _frame(0.3, 1.2, 0.3)
    for mu in (0.05, 0.15):
        g = graph_limit(arc, "l", friction=mu)
        assert g.k == pytest.approx(mu, abs=1e-9)
        assert g.k_virtual_work == pytest.approx(mu, abs=1e-9)
        assert set(g.mechanism.sliding) == {0, 1}
    assert graph_multiplier(arc, "l", friction=0.4) == pytest.approx(0.25, abs=1e-9)


def test_mirror_symmetry_of_a_symmetric_arcade(semicircle):
    arc = arcade([semicircle] * 3, 8.0, [2.5, 1.8, 1.8, 2.5])
    gl, gr = graph_limit(arc, "l"), graph_limit(arc, "r")
    assert gl.k == pytest.approx(gr.k, abs=1e-9)
    gm = graph_limit(arc.mirrored(), "r")
    assert gm.k == pytest.approx(gl.k, abs=1e-9)
    # the mirror's hinges are the original's: the same contacts, the same ends' names
    assert sorted(h.place for h in gm.hinges) == sorted(h.place for h in gl.hinges)


def test_two_and_three_span_arcades(semicircle):
    """On low piers the end span governs alone, as the one-span arch on piers does; on tall
    piers with slender inner piers the whole arcade sways: every pier's foot a hinge, 1 dof."""
    low = arcade([semicircle] * 2, 4.0, 2.0)
    g = graph_limit(low, "l")
    assert g.k == pytest.approx(graph_limit(arcade([semicircle], 4.0, 2.0), "l").k, abs=1e-9)
    assert {h.place.split(",")[0].split(" joint")[0] for h in g.hinges} == {"span 2",
                                                                            "pier 3 foot"}
    for spans, k in ((2, 0.140874), (3, 0.139911)):
        arc = arcade([semicircle] * spans, 8.0, [2.5] + [1.8] * (spans - 1) + [2.5])
        g = graph_limit(arc, "l")
        assert g.k == pytest.approx(k, abs=5e-7)
        assert g.k_virtual_work == pytest.approx(g.k, abs=1e-9)
        assert g.mechanism.dof == 1
        feet = sorted(h.place for h in g.hinges if "foot" in h.place)
        assert feet == [f"pier {p} foot, right face" for p in range(2, spans + 1)] + \
            [f"pier {spans + 1} foot, outer face"]
        assert len(g.hinges) == 3 * spans + 1
        # the static optimum's forces hold every block: no tension, |V| free
        assert np.all(g.forces[:, :2] >= -1e-6 * np.abs(g.forces).max())


def test_refusals_and_outcomes():
    arc = _frame(0.3, 1.2, 0.3)
    with pytest.raises(ArchInputError, match="direction: 'x'; allowed 'l' or 'r'"):
        graph_limit(arc, "x")
    with pytest.raises(ArchInputError, match="friction"):
        graph_limit(arc, "l", friction=-1)
    with pytest.raises(ArchInputError, match="arcade: expected an Arcade"):
        graph_limit(nominal_arch(), "l")
    # a block on a point-wide... a beam over a column that stands outside its base: no
    # equilibrium under its own weight
    blocks = (Block([(0, 0), (1, 0), (1, 1), (0, 1)], "pier"),
              Block([(0.9, 1), (5, 1), (5, 1.2), (0.9, 1.2)], "beam"))
    contacts = (Contact(GROUND, 0, [(0, 0), (1, 0)]), Contact(0, 1, [(0.9, 1), (1, 1)]))
    with pytest.raises(CannotStandError):
        graph_limit(Arcade(blocks, contacts), "l")


def test_record_says_what_and_how(semicircle):
    g = graph_limit(arcade([semicircle], 4.0, 2.0), "r")
    d = g.to_dict()
    assert d["direction"] == "r" and d["k"] == g.k and "HiGHS" in d["method"]
    assert d["mechanism"]["hinges"][0] == {"contact": 0, "end": 1,
                                           "place": "pier 1 foot, outer face"}
    assert np.asarray(d["forces"]).shape == (len(arcade([semicircle], 4.0, 2.0).contacts), 3)


@pytest.mark.parametrize("b, h, depth", [(0.3, 1.2, 0.3), (0.2, 2.5, 0.6)])
def test_mechanism_kinematics_of_the_frame(b, h, depth):
    """The LP's hinges rebuilt as a linkage (mechanism_velocities): one degree of freedom, the
    LP's velocities up to scale; its generalised mass per unit column rotation rate is
    Makris & Vassiliou's M(0) = 8/3 m R^2 (1 + 3 gamma), gamma = beam / columns' mass, and its
    frequency parameter their p^2 (both to 1e-9)."""
    from archrock.statics.graph import generalized_mass, mechanism_velocities

    arc = _frame(b, h, depth)
    g = graph_limit(arc, "l")
    basis = mechanism_velocities(arc, [(x.contact, x.end) for x in g.hinges])
    assert basis.shape == (1, 3, 3)
    w_lp = g.mechanism.velocities[0, 2]
    lp = g.mechanism.velocities / abs(w_lp)  # per unit rotation rate of column 1, LP's sense
    v = basis[0] / basis[0][0, 2] * np.sign(w_lp)
    assert np.allclose(v, lp, atol=1e-9 * np.abs(lp).max())
    m, m_b = arc.masses[0], arc.masses[2]
    gamma = m_b / (2 * m)
    R2 = b * b + h * h
    assert generalized_mass(arc, v) == pytest.approx(8 / 3 * m * R2 * (1 + 3 * gamma),
                                                     rel=1e-9)
    # the frequency parameter: Q / (M sin alpha) = p^2 = (3 g / 4 R)(1 + 2 gamma)/(1 + 3 gamma),
    # and the mechanism starts at lambda = Q / H = the LP's k
    from archrock.statics.graph import generalized_loads
    from archrock.units import G

    q, hh = generalized_loads(arc, v)
    R = np.sqrt(R2)
    p2 = 3 * G / (4 * R) * (1 + 2 * gamma) / (1 + 3 * gamma)
    assert q / (generalized_mass(arc, v) * b / R) == pytest.approx(p2, rel=1e-9)
    assert q / hh == pytest.approx(g.k, abs=1e-9)
    # the beam lifted off its columns: each column rocks on its own foot corner (1 + 1) and the
    # beam is free (3): five degrees of freedom, the case a four-link model cannot follow
    more = mechanism_velocities(arc, [(0, 1), (1, 1)], lift_off=[2, 3])
    assert more.shape[0] == 5
    with pytest.raises(ArchInputError, match=r"hinges: \(9, 0\)"):
        mechanism_velocities(arc, [(9, 0)])


@pytest.mark.parametrize("mu", [0.4, 0.5, 0.6])
def test_one_span_friction_equals_the_chain_friction_lp(mu, semicircle):
    """With Coulomb rows the one-span arcade is the chain's friction LP (statics.friction):
    below mu = 0.5045 the arch slides outward on the far pier's top (docs/piers.md: k = 0.069873
    at 0.4, 0.164499 at 0.5), above it the frictionless mechanism."""
    from archrock.statics.friction import friction_analysis

    chain = with_piers(semicircle, 4.0, 2.0, courses=2)
    fr = friction_analysis(chain, mu)
    arc = arcade([semicircle], 4.0, 2.0, courses=2)
    for d in "lr":
        g = graph_limit(arc, d, friction=mu)
        assert g.k == pytest.approx(fr.direction(d).multiplier, abs=1e-9)
        assert g.k_virtual_work == pytest.approx(g.k, abs=1e-9)
        sliding = {c for c in g.mechanism.sliding}
        assert sliding == ({11} if d == "l" and mu < 0.5045 else
                           {2} if mu < 0.5045 else set())


def test_loads_ride_on_their_voussoir(semicircle):
    """A point load on a voussoir (8 t/m on voussoir 6) is carried into the arcade's block: the
    same masses as the chain (to rounding: the arcade sums its blocks by its own code), and the chain's k in both directions (k_r < 0: the
    loaded arch on these piers needs a push toward +x to stand, in both programs alike)."""
    from archrock.geometry import Arch, Load

    a = semicircle
    loaded = Arch(a.spans, a.radii, a.thicknesses, a.density, "loaded",
                  (Load(6, 8000.0, (2.0, 5.5)),))
    chain = with_piers(loaded, 4.0, 2.0)
    arc = arcade([loaded], 4.0, 2.0)
    np.testing.assert_allclose(arc.masses, chain.masses, rtol=1e-12)
    for d, k in (("l", 0.139803), ("r", -0.083677)):
        assert graph_multiplier(arc, d) == pytest.approx(static_multiplier(chain, d)[0],
                                                         abs=1e-9)
        assert graph_multiplier(arc, d) == pytest.approx(k, abs=5e-7)


@pytest.mark.slow
def test_random_arcades():
    """25 random arcades (1 to 3 spans of five arch shapes, pier heights 1-10 m, widths 1.5-3.5
    m, 1 or 2 courses, every third with friction 0.6), both directions: the mechanism's virtual
    work equals the LP's k (measured: 6e-14 at worst), and a one-span case without friction is
    the chain's LP."""
    rng = np.random.default_rng(1)
    shapes = [nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9),
              nominal_arch(radius=6, embrace_deg=120, thickness=0.7, voussoirs=7),
              family_arch("pointed", 8, 6, 0.7, 8),
              family_arch("elliptical", 12, 4, 0.9, 11),
              family_arch("three-centred", 10, 3.5, 0.8, 9)]
    checked = 0
    for trial in range(25):
        n = int(rng.integers(1, 4))
        arches = [shapes[i] for i in rng.integers(0, len(shapes), n)]
        heights = list(rng.uniform(1, 10, n + 1))
        widths = list(rng.uniform(1.5, 3.5, n + 1))
        courses = [int(c) for c in rng.integers(1, 3, n + 1)]
        mu = None if trial % 3 else 0.6
        try:
            arc = arcade(arches, heights, widths, courses=courses)
        except ArchInputError as exc:  # an inner pier narrower than its two springings
            assert "narrower than the two springing joints" in str(exc)
            continue
        for d in "lr":
            g = graph_limit(arc, d, friction=mu)
            assert abs(g.k_virtual_work - g.k) < 1e-9 * max(1.0, abs(g.k))
            checked += 1
            if n == 1 and mu is None:
                chain = with_piers(arches[0], heights[0], widths[0], courses=courses[0],
                                   height_right=heights[1], width_right=widths[1],
                                   courses_right=courses[1])
                assert g.k == pytest.approx(static_multiplier(chain, d)[0], abs=1e-9)
    assert checked >= 40
