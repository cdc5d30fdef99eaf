"""Four-link mechanism: equilibrium at the multiplier, coefficients against finite differences,
energy conservation, symmetry and mirror images, Housner's block as a four-link case, bad input.

The finite-difference checks rebuild every link position from the loop closure
(:func:`archrock.dynamics.fourlink.configuration`) and differentiate positions numerically: they share
no derivative formula with :func:`archrock.dynamics.fourlink.coefficients`.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from archrock import geometry
from archrock.dynamics import impact, fourlink as mechanism
from archrock.statics import limit
from archrock.errors import ArchInputError
from archrock.statics.limit import Hinge, Mechanism
from archrock.dynamics.fourlink import FourLink, configuration, four_link

G = 9.81
SEEDS = (0, 1, 2, 3, 5, 8, 13, 21)


def _mechs(arch):
    lim = limit.limit_analysis(arch, verify=False)
    return lim, four_link(arch, lim.mechanism_l), four_link(arch, lim.mechanism_r)


@pytest.fixture(scope="module")
def opp(oppenheim):
    return oppenheim.limit, oppenheim.left, oppenheim.right


@pytest.fixture(scope="module")
def randoms():
    return [_mechs(geometry.random_arch(seed=s, spread_span=0.1, spread_thickness=0.1,
                                        spread_radius=0.05)) for s in SEEDS]


# ------------------------------------------------------------------------- (a) equilibrium
def test_static_multiplier_oppenheim(opp):
    lim, ml, mr = opp
    assert lim.k_l == pytest.approx(0.3700, abs=5e-5)
    assert ml.static_multiplier() == pytest.approx(-lim.k_l, abs=1e-10)
    assert mr.static_multiplier() == pytest.approx(lim.k_r, abs=1e-10)
    # the equation itself: M*0 + L*0 + F g = P xg'' at xg'' = -k_l g (M_l) / +k_r g (M_r)
    for fl, a in ((ml, -lim.k_l * G), (mr, lim.k_r * G)):
        M, L, F, P = fl.coefficients(0.0)
        assert abs(F * G - P * a) <= 1e-10 * abs(F * G)
        assert F > 0 and M > 0


def test_static_multiplier_random(randoms):
    for lim, ml, mr in randoms:
        assert ml.static_multiplier() == pytest.approx(-lim.k_l, abs=1e-10)
        assert mr.static_multiplier() == pytest.approx(lim.k_r, abs=1e-10)
        # P > 0 for M_l (opened by forces toward +x, i.e. xg'' < 0): P xg'' > 0 drives it open
        assert ml.coefficients(0.0)[3] < 0 < mr.coefficients(0.0)[3]


# ------------------------------------------------------------------------- (b) finite differences
def _positions(phi, geo):
    """Centroids (3, 2) and rotations (3,) of the links at phi, from the loop closure only."""
    bx, by, cx, cy, th1, th2, th3, ok = configuration(phi, geo)
    assert ok
    a = np.array(geo[0:2])
    b0 = np.array(geo[2:4])
    d = np.array(geo[6:8])
    refs_now = (a, np.array([bx, by]), d)
    refs_0 = (a, b0, d)
    out = np.empty((3, 2))
    for k, th in enumerate((th1, th2, th3)):
        c, s = math.cos(th), math.sin(th)
        r = np.array(geo[12 + 2 * k:14 + 2 * k]) - refs_0[k]
        out[k] = refs_now[k] + np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]])
    return out, np.array([th1, th2, th3])


def _fd_coefficients(phi, geo, h=1e-5):
    """M, F, P by central differences of positions (and M' of the code's M for L)."""
    gp, tp = _positions(phi + h, geo)
    gm, tm = _positions(phi - h, geo)
    dg = (gp - gm) / (2 * h)
    dth = (tp - tm) / (2 * h)
    m = np.array(geo[9:12])
    inertia = np.array(geo[18:21])
    M = float(np.sum(m * np.sum(dg**2, axis=1)) + np.sum(inertia * dth**2))
    P = float(-np.sum(m * dg[:, 0]))
    pot = lambda q: float(np.sum(m * _positions(q, geo)[0][:, 1]))
    F = (pot(phi + h) - pot(phi - h)) / (2 * h)
    Mc = lambda q: mechanism.coefficients(q, geo)[0]
    L = (Mc(phi + h) - Mc(phi - h)) / (4 * h)
    return M, L, F, P


@pytest.mark.parametrize("which", range(4))
def test_coefficients_vs_finite_differences(opp, randoms, which):
    systems = [opp] + randoms[:3]
    _, ml, mr = systems[which]
    for fl in (ml, mr):
        geo = fl.geo
        scale_m = fl.coefficients(0.0)[0]
        scale_f = abs(fl.coefficients(0.0)[3])
        for phi in np.linspace(0.0, 1.4 * fl.phi_unstable, 6):
            M, L, F, P = fl.coefficients(phi)
            Mf, Lf, Ff, Pf = _fd_coefficients(phi, geo)
            assert M == pytest.approx(Mf, rel=1e-7)
            assert L == pytest.approx(Lf, rel=1e-6, abs=1e-6 * scale_m)
            assert F == pytest.approx(Ff, abs=1e-7 * scale_f)
            assert P == pytest.approx(Pf, abs=1e-7 * scale_f)
            # the module's own potential agrees with the one rebuilt from positions
            pot = np.sum(geo[9:12] * _positions(phi, geo)[0][:, 1]) - np.sum(geo[9:12] * geo[[13, 15, 17]])
            assert mechanism.potential(phi, geo) == pytest.approx(pot, abs=1e-9 * scale_f)


def test_L_is_not_trivially_zero(opp):
    # the L term matters: on the arch M varies with phi
    _, ml, _ = opp
    phi = 0.5 * ml.phi_unstable
    assert abs(ml.coefficients(phi)[1]) > ml.coefficients(phi)[0]  # |M'/M| ~ 10 per rad


# ------------------------------------------------------------------------- (c) energy
def _free_rhs(fl):
    def rhs(t, y):
        M, L, F, _ = fl.coefficients(y[0])
        return [y[1], -(L * y[1] ** 2 + F * G) / M]
    return rhs


def _close(t, y):
    return y[0]


_close.terminal = True
_close.direction = -1


def _turn(t, y):
    return y[1]


_turn.direction = -1


@pytest.mark.parametrize("which", [0, 1, 2])
def test_energy_conserved_release_from_rest(opp, randoms, which):
    _, ml, mr = ([opp] + randoms)[which]
    for fl in (ml, mr):
        phi0 = 0.3 * fl.phi_unstable
        sol = solve_ivp(_free_rhs(fl), (0.0, 3.0), [phi0, 0.0], method="DOP853", rtol=1e-12,
                        atol=1e-14, events=_close, dense_output=True)
        assert sol.status == 1  # it swings back to phi = 0 (the arc) before 3 s
        t_hit = sol.t_events[0][0]
        tt = np.linspace(0.0, t_hit, 200)
        e0 = fl.energy(phi0, 0.0)
        assert e0 > 0
        e = np.array([fl.energy(p, w) for p, w in sol.sol(tt).T])
        assert np.max(np.abs(e - e0)) / e0 < 1e-8
        # all potential energy turned into kinetic energy at phi = 0
        w_hit = sol.y_events[0][0][1]
        assert 0.5 * fl.coefficients(0.0)[0] * w_hit**2 == pytest.approx(e0, rel=1e-8)


def test_energy_conserved_outward_arc(opp, randoms):
    for _, ml, mr in [opp] + randoms[:2]:
        for fl in (ml, mr):
            # outward rate whose energy lifts the arch to about half the unstable rotation
            e_target = G * mechanism.potential(0.5 * fl.phi_unstable, fl.geo)
            w0 = math.sqrt(2 * e_target / fl.coefficients(0.0)[0])
            sol = solve_ivp(_free_rhs(fl), (0.0, 3.0), [0.0, w0], method="DOP853", rtol=1e-12,
                            atol=1e-14, events=(_close, _turn), dense_output=True)
            assert sol.status == 1
            t_back = sol.t_events[0][0]
            e = np.array([fl.energy(p, w) for p, w in sol.sol(np.linspace(0, t_back, 200)).T])
            assert np.max(np.abs(e - e_target)) / e_target < 1e-8
            # one turning point, at the rotation whose potential energy equals the initial energy
            assert sol.t_events[1].size == 1
            assert sol.y_events[1][0][0] == pytest.approx(0.5 * fl.phi_unstable, rel=1e-8)
            # time reversibility of the conservative motion: it returns with the opposite rate
            assert sol.y_events[0][0][1] == pytest.approx(-w0, rel=1e-8)


# ------------------------------------------------------------------------- (d) symmetry, mirror
def _assert_mirror_images(a, b, phi, rel, rel_l):
    """Mechanisms ``a`` and ``b`` have the same equation of motion at ``phi`` but for the sign of
    the ground's term P; L, a difference of near-equal terms, to ``rel_l`` (and rel * M)."""
    Ma, La, Fa, Pa = a.coefficients(phi)
    Mb, Lb, Fb, Pb = b.coefficients(phi)
    assert Ma == pytest.approx(Mb, rel=rel)
    assert La == pytest.approx(Lb, rel=rel_l, abs=rel * Mb)
    assert Fa == pytest.approx(Fb, rel=rel)
    assert Pa == pytest.approx(-Pb, rel=rel)


def test_symmetric_arch_same_equation(opp):
    _, ml, mr = opp
    for phi in (0.0, 0.01, 0.05, 0.1, 0.2):
        _assert_mirror_images(mr, ml, phi, 1e-12, 1e-9)
    assert mr.phi_unstable == pytest.approx(ml.phi_unstable, rel=1e-10)


def test_mirrored_arch_swaps_mechanisms():
    for seed in (4, 7, 11):
        arch = geometry.random_arch(seed=seed)
        lim, ml, mr = _mechs(arch)
        limm, mlm, mrm = _mechs(arch.mirrored())
        assert limm.k_l == pytest.approx(lim.k_r, rel=1e-10)
        assert limm.k_r == pytest.approx(lim.k_l, rel=1e-10)
        assert not math.isclose(lim.k_l, lim.k_r, rel_tol=1e-3)  # really irregular
        for phi in (0.0, 0.03, 0.08, 0.15):
            for a, b in ((mlm, mr), (mrm, ml)):
                _assert_mirror_images(a, b, phi, 1e-10, 1e-8)
        # and the two mechanisms of the irregular arch really differ
        assert not math.isclose(ml.coefficients(0.0)[0], mr.coefficients(0.0)[0], rel_tol=1e-4)


# ------------------------------------------------------------------------- (e) Housner's block
def _frame(b, h, m=1000.0, beam=1e-9, span=6.0):
    """Rocking frame (Makris & Vassiliou): two identical columns (half-width b, half-height h)
    carrying a cap beam of negligible mass, opening as M_l (forces toward +x): the columns
    rotate clockwise about their bottom-right corners, hinges at their top-left corners."""
    x1, x2 = 0.0, span
    A = (x1 + b, 0.0)
    B = (x1 - b, 2 * h)
    C = (x2 - b, 2 * h)
    D = (x2 + b, 0.0)
    R2 = b * b + h * h
    mb = beam * m
    masses = np.array([m, mb, m])
    cents = np.array([[x1, h], [0.5 * (B[0] + C[0]), 2 * h + 0.1], [x2, h]])
    inert = np.array([m * R2 / 3.0, mb * span**2 / 12.0, m * R2 / 3.0])
    # clockwise rotation of AB opens the mechanism: theta_1 = -phi
    return FourLink("l", np.array([A, B, C, D]), -1.0, masses, cents, inert), m


@pytest.mark.parametrize("b,h", [(0.25, 1.0), (0.5, 1.5), (0.2, 2.5)])
def test_housner_block_as_four_link(b, h):
    fl, m = _frame(b, h)
    R = math.hypot(b, h)
    alpha = math.atan2(b, h)
    assert fl.static_multiplier() == pytest.approx(-math.tan(alpha), rel=1e-8)
    assert fl.phi_unstable == pytest.approx(alpha, rel=1e-8)
    assert fl.phi_dead > fl.phi_unstable
    p2 = 3 * G / (4 * R)
    for phi in np.linspace(0.0, 1.5 * alpha, 7):
        M, L, F, P = fl.coefficients(phi)
        assert M == pytest.approx(2 * 4.0 / 3.0 * m * R * R, rel=1e-8)
        assert abs(L) < 1e-8 * M
        assert F == pytest.approx(2 * m * R * math.sin(alpha - phi), abs=1e-8 * m * R)
        assert P == pytest.approx(-2 * m * R * math.cos(alpha - phi), rel=1e-8)
        # Housner's equation of free rocking: phi'' = -p^2 sin(alpha - phi)
        if abs(alpha - phi) > 1e-3:
            assert G * F / (M * math.sin(alpha - phi)) == pytest.approx(p2, rel=1e-8)
    # linearised about the unstable position: phi'' = -(g F'(alpha)/M) (phi - alpha) = p^2 (phi - alpha)
    e = 1e-6
    dF = (fl.coefficients(alpha + e)[2] - fl.coefficients(alpha - e)[2]) / (2 * e)
    assert -G * dF / fl.coefficients(alpha)[0] == pytest.approx(p2, rel=1e-7)
    assert math.sqrt(p2) == pytest.approx(math.sqrt(3 * G / (4 * R)), rel=1e-12)


@pytest.mark.parametrize("b,h", [(0.25, 1.0), (0.5, 1.5), (1.0, 1.0), (0.1, 3.0)])
def test_housner_restitution(b, h):
    """One rectangular block rocking from its right corner onto its left one."""
    m = 2.0
    R2 = b * b + h * h
    inertia = m * R2 / 3.0
    g_pt = np.array([0.0, h])

    def field(pivot, omega):
        r = g_pt - np.array(pivot)
        return np.array([-omega * r[1], omega * r[0]]), omega

    # old motion: clockwise about (b, 0), rate per unit opening coordinate; new: anticlockwise about (-b, 0)
    v_old, w_old = field((b, 0.0), -1.0)
    v_new, w_new = field((-b, 0.0), 1.0)
    c = impact.projection_ratio([m], [inertia], v_old, [w_old], v_new, [w_new])
    alpha = math.atan2(b, h)
    assert c == pytest.approx(max(0.0, 1 - 1.5 * math.sin(alpha) ** 2), abs=1e-14)


# ------------------------------------------------------------------------- (f) positions, bad input
def test_unstable_and_dead_points(opp, randoms):
    for _, ml, mr in [opp] + randoms:
        for fl in (ml, mr):
            pu = fl.phi_unstable
            F0 = fl.coefficients(0.0)[2]
            assert abs(fl.coefficients(pu)[2]) < 1e-10 * F0
            assert all(fl.coefficients(p)[2] > 0 for p in np.linspace(0, pu, 30)[:-1])
            assert fl.coefficients(1.05 * pu)[2] < 0
            assert fl.phi_dead > pu
            lim = fl.default_limit()
            assert pu < lim < fl.phi_dead


def test_oppenheim_unstable_rotation(opp):
    _, ml, _ = opp
    # measured: ~3.96 deg for Oppenheim's arch
    assert ml.phi_unstable == pytest.approx(0.0690647, rel=1e-5)


def test_four_link_bad_input(opp):
    arch = geometry.oppenheim_arch()
    lim, _, _ = opp
    # every hinge on the intrados: joints cannot all open in one admissible field
    bad = Mechanism("l", tuple(Hinge(j, "intrados") for j in (0, 3, 5, 7)), 0.37)
    with pytest.raises(ArchInputError, match="admit no opening motion"):
        four_link(arch, bad)
    # M_l's hinges read as M_r: they open under forces toward +x, not -x
    wrong = Mechanism("r", lim.mechanism_l.hinges, lim.k_l)
    with pytest.raises(ArchInputError, match="do not open"):
        four_link(arch, wrong)
    with pytest.raises(ArchInputError, match="4 distinct joints"):
        four_link(arch, Mechanism("l", (Hinge(0, "intrados"), Hinge(3, "extrados"),
                                        Hinge(3, "intrados"), Hinge(7, "extrados")), 0.4))
    with pytest.raises(ArchInputError, match="direction"):
        four_link(arch, Mechanism("x", lim.mechanism_l.hinges, lim.k_l))


# ------------------------------------------------------------------ spline tables (fast kernel)
@pytest.mark.parametrize("seed", [None, 3, 315])
def test_tabulated_coefficients_match_exact(seed):
    """The fast kernel's spline tables reproduce the exact M, L, F, P to 1e-8 of their scale
    over the whole range the integrator visits (slightly below 0 up to the rotation limit)."""
    from archrock.dynamics.fourlink import fast_coefficients
    from archrock.dynamics.response import prepare

    arch = geometry.oppenheim_arch() if seed is None else geometry.random_arch(seed=seed)
    model = prepare(arch, "momentum")
    for fl, lim, tab in ((model.mech_l, model.phi_limit_l, model.tables[0]),
                         (model.mech_r, model.phi_limit_r, model.tables[1])):
        scale = np.abs(np.array(fl.coefficients(0.0)))
        for phi in np.linspace(-1e-3, lim, 997):
            exact = np.array(fl.coefficients(phi))
            approx = np.array(fast_coefficients(phi, tab))
            assert np.all(np.abs(approx - exact) <= 1e-8 * scale)
        # outside the table the exact formulas are used
        assert fast_coefficients(2 * lim, tab) == fl.coefficients(2 * lim)


def test_coefficients_are_python_floats_without_numba(without_numba):
    """FourLink.coefficients gives Python floats with and without numba (numpy scalars broke
    JSON output in the pure-Python mode)."""
    import json

    script = ("import json; from archrock import geometry, _jit; "
              "from archrock.statics import limit; from archrock.dynamics import fourlink; "
              "a = geometry.oppenheim_arch(); r = limit.limit_analysis(a, verify=False); "
              "c = fourlink.four_link(a, r.mechanism_l).coefficients(0.01); "
              "print(json.dumps([_jit.HAVE_NUMBA, [type(v).__name__ for v in c], list(c)]))")
    have_numba, types, values = json.loads(without_numba("-c", script, timeout=300))
    assert not have_numba and types == ["float"] * 4
    a = geometry.oppenheim_arch()
    here = four_link(a, limit.limit_analysis(a, verify=False).mechanism_l).coefficients(0.01)
    assert all(type(v) is float for v in here)
    assert values == pytest.approx(list(here), rel=1e-12)
