"""Limit analysis with Coulomb friction (archrock.statics.friction): Cocchetti and Rizzi's semicircle
(Frattura ed Integrita Strutturale 51, 2020), the frictionless limit at large friction, the friction
needed against the friction multiplier and against the collapse thrust line, mirror images,
scale, an independent voussoir-by-voussoir LP, input checks and the command line."""

import json
import math

import numpy as np
import pytest
from scipy.optimize import linprog

from archrock.statics import friction, limit
from archrock.cli import main
from archrock.errors import ArchInputError, CannotStandError, NoMechanismError
from archrock.geometry import (Arch, Load, family_arch, nominal_arch, oppenheim_arch,
                               random_arch)

K_OPPENHEIM = 0.3700097380218772
# Cocchetti and Rizzi (2020), Table 3 and eq. (4): complete semicircle, radial joints, weight
# along the centreline ("CCR" solution)
CR_ETA_R, CR_MU_RM = 0.107426, 0.395832   # least thickness / radius, friction at the transition
CR_MU_MS, CR_ETA_MS = 0.309215, 0.200637  # below mu_ms no thickness stands; eta at mu_ms


def _irregular(seed, n=9):
    return random_arch(nominal_arch(10.0, 157.5, 1.5, n), seed=seed, spread_span=0.15,
                       spread_thickness=0.15, spread_radius=0.08)


def _centreline_semicircle(n, t_over_r=0.2, radius=1.0):
    """A semicircle whose weight lies on its centreline, as Cocchetti and Rizzi take it: nearly
    massless masonry (1 kg/m^3) with a point mass at the centroid of each voussoir's arc of the
    mean radius, proportional to its span (10^9 times the masonry's: 1e-9 of the weight off)."""
    a = nominal_arch(radius, 180.0, t_over_r * radius, n)
    psi = a.joint_angles
    mid, half = 0.5 * (psi[:-1] + psi[1:]), 0.5 * a.spans
    rc = radius * np.sin(half) / half
    loads = tuple(Load(i, 1e9 * radius**2 * a.spans[i], (rc[i] * math.cos(mid[i]),
                                                        rc[i] * math.sin(mid[i])))
                  for i in range(n))
    return Arch(a.spans, a.radii, a.thicknesses, 1.0, "centreline semicircle", loads)


# ---------------------------------------------------------------------------- published values
@pytest.fixture(scope="module")
def centreline_360():
    return _centreline_semicircle(360)


def test_cocchetti_rizzi_purely_rotational_range(centreline_360):
    """Above mu_rm the least thickness is Heyman's (friction does not matter) and its collapse
    needs exactly mu_rm: the springings are about to slide."""
    a = centreline_360
    mt = friction.friction_minimum_thickness(a, 10.0)
    assert mt.ratio == pytest.approx(CR_ETA_R, abs=2e-6)
    assert mt.ratio == pytest.approx(limit.minimum_thickness(a).ratio, rel=1e-6)
    need = friction.friction_needed(a.with_thickness_factor(mt.factor))
    assert need["l"] == pytest.approx(CR_MU_RM, abs=2e-6)
    assert need["r"] == pytest.approx(need["l"], abs=1e-9)
    # the same least thickness just above mu_rm, a thicker one just below
    above = friction.friction_minimum_thickness(a, CR_MU_RM + 1e-4)
    below = friction.friction_minimum_thickness(a, CR_MU_RM - 5e-3)
    assert above.ratio == pytest.approx(mt.ratio, rel=1e-6)
    assert below.ratio > mt.ratio * 1.02


def test_cocchetti_rizzi_mixed_and_sliding_limits(centreline_360):
    a = centreline_360
    # just above mu_ms the least thickness reaches ~1.87 times Heyman's
    near = friction.friction_minimum_thickness(a, CR_MU_MS + 5e-6)
    assert near.ratio == pytest.approx(CR_ETA_MS, abs=2e-4)
    with pytest.raises(CannotStandError, match="no thickness stands .* friction 0.309"):
        friction.friction_minimum_thickness(a, CR_MU_MS - 2e-4)


def test_semicircle_true_weights_thickness_rises_as_friction_falls():
    """archrock's own weights (each voussoir at its sector's centroid: Milankovitch's 0.1075):
    t/R = 0.1075 for mu above ~0.396, rising as mu falls, nothing below ~0.309."""
    a = nominal_arch(10.0, 180.0, 1.0, 60)
    t_free = limit.minimum_thickness(a).ratio
    assert t_free == pytest.approx(0.1075, abs=1e-4)
    need = friction.friction_needed(a.with_thickness_factor(limit.minimum_thickness(a).factor))
    assert need["l"] == pytest.approx(0.396, abs=1e-3)
    assert friction.friction_minimum_thickness(a, 0.5).ratio == pytest.approx(t_free, rel=1e-6)
    mus = [0.39, 0.37, 0.35, 0.33, 0.31]
    t = [friction.friction_minimum_thickness(a, mu).ratio for mu in mus]
    assert t[0] > t_free and np.all(np.diff(t) > 0)
    assert t[-1] == pytest.approx(0.1976, abs=1e-3)
    for mu in (0.305, 0.2):
        with pytest.raises(CannotStandError, match="no thickness stands"):
            friction.friction_minimum_thickness(a, mu)


# ---------------------------------------------------------------------------- frictionless limit
def test_large_friction_gives_the_frictionless_multiplier():
    a = oppenheim_arch()
    for mu in (1.0, 10.0, 1e6):
        res = friction.friction_analysis(a, mu)
        for d in ("l", "r"):
            fd = res.direction(d)
            assert fd.multiplier == pytest.approx(K_OPPENHEIM, abs=1e-12)
            assert fd.frictionless == pytest.approx(K_OPPENHEIM, abs=1e-12)
            assert not fd.sliding_governs
    assert res.k == pytest.approx(0.370010, abs=5e-7)


def test_friction_needed_is_where_the_multiplier_drops():
    """Cross-check of two computations: just above the friction needed the friction LP gives
    the frictionless multiplier, just below it a lower one."""
    for a in (oppenheim_arch(), _irregular(3), family_arch("pointed", 10.0, 8.0, 0.8, 8)):
        need = friction.friction_needed(a)
        for d in ("l", "r"):
            mu = need[d]
            up = friction.friction_analysis(a, mu * (1 + 1e-5)).direction(d)
            down = friction.friction_analysis(a, mu * (1 - 1e-3)).direction(d)
            assert up.multiplier == pytest.approx(up.frictionless, rel=1e-9)
            assert not up.sliding_governs
            assert down.multiplier < down.frictionless - 1e-6
            assert down.sliding_governs
            # the sliding joints are at the friction limit, the others below it
            assert down.ratios[list(down.joints)] == pytest.approx(down.mu, rel=1e-6)
            assert np.all(down.ratios <= down.mu * (1 + 1e-7))


def test_friction_needed_is_the_largest_ratio_on_the_collapse_thrust_line():
    """Where the four hinges fix the collapse thrust line, the friction needed is its largest
    |T|/N (third computation: the kinematic mechanism's hinges, not an LP)."""
    for a in (oppenheim_arch(), _irregular(5), _irregular(11, 12)):
        res = limit.limit_analysis(a)
        need = friction.friction_needed(a)
        for d, th in (("l", res.thrust_l), ("r", res.thrust_r)):
            T, N = friction.joint_shear_normal(a, th)
            assert np.all(N > 0)
            assert need[d] == pytest.approx(float(np.max(np.abs(T) / N)), rel=1e-8)
    # Oppenheim's arch: the springing on the side the loads push toward
    opp = friction.friction_analysis(oppenheim_arch(), 1.0)
    assert opp.l.friction_needed == pytest.approx(0.495132, abs=1e-6)
    assert opp.l.joints == (7,) and opp.r.joints == (0,)


def _sweep_arches():
    for seed in range(60):
        n = 5 + seed % 12
        yield random_arch(nominal_arch(10.0, 140 + seed % 40, 1.0 + 0.05 * (seed % 10), n),
                          seed=seed, spread_span=0.2, spread_thickness=0.2, spread_radius=0.1)
        if seed % 4 == 0:
            yield random_arch(family_arch("circular", 10, 4, 1.0, n, exact=False), seed=seed,
                              spread_tilt_deg=6)
    for shape, rise in (("pointed", 7), ("elliptical", 3), ("three-centred", 3.5),
                        ("parabolic", 5), ("catenary", 5)):
        for n in (6, 9, 13):
            yield family_arch(shape, 10, rise, 1.0, n)


@pytest.mark.slow
def test_friction_needed_equals_the_hinge_thrust_line_on_many_arches():
    """Irregular circular arches, tilted joints, every family: the bisection's friction needed
    is the largest |T|/N of the thrust line through the kinematic mechanism's hinges, and just
    above it sliding does not govern (on 163 arches the worst difference was 2e-13)."""
    from archrock.errors import GeometryOutcome

    checked = 0
    for a in _sweep_arches():
        try:
            res = limit.limit_analysis(a)
        except GeometryOutcome:
            continue
        need = friction.friction_needed(a)
        for d, th in (("l", res.thrust_l), ("r", res.thrust_r)):
            T, N = friction.joint_shear_normal(a, th)
            assert need[d] == pytest.approx(float(np.max(np.abs(T) / N)), rel=1e-9), a.name
            up = friction.friction_analysis(a, need[d] * (1 + 1e-6)).direction(d)
            assert not up.sliding_governs, a.name
        checked += 1
    assert checked > 60


def test_mirror_image_swaps_the_directions():
    a = _irregular(7)
    m = a.mirrored()
    need, need_m = friction.friction_needed(a), friction.friction_needed(m)
    assert need_m["l"] == pytest.approx(need["r"], rel=1e-9)
    assert need_m["r"] == pytest.approx(need["l"], rel=1e-9)
    mu = 0.8 * min(need.values())
    res, res_m = friction.friction_analysis(a, mu), friction.friction_analysis(m, mu)
    for d, e in (("l", "r"), ("r", "l")):
        assert res_m.direction(d).multiplier == pytest.approx(res.direction(e).multiplier,
                                                               rel=1e-9)
        assert res_m.direction(d).joints == tuple(sorted(a.n - j for j in res.direction(e).joints))


@pytest.mark.parametrize("radius", [0.01, 10.0, 1e4])
def test_nondimensional_at_every_scale(radius):
    """The same proportions at 1 cm, 10 m and 10 km: the same friction figures."""
    a = nominal_arch(radius, 157.5, 0.15 * radius, 7)
    need = friction.friction_needed(a)
    assert need["l"] == pytest.approx(0.495132, abs=1e-6)
    res = friction.friction_analysis(a, 0.4)
    assert res.l.multiplier == pytest.approx(0.2637586, abs=1e-6)
    mt = friction.friction_minimum_thickness(a, 0.4)
    assert mt.ratio == pytest.approx(0.059219, abs=2e-5)


# ---------------------------------------------------------------------------- second formulation
def _voussoir_lp(arch, direction, mu):
    """The largest multiplier with friction mu from each voussoir's own equilibrium: unknowns
    N_j, T_j, m_j at every joint (normal force, shear, moment about the joint's intrados end)
    and lambda; 0 <= m_j <= L_j N_j, |T_j| <= mu N_j."""
    n = arch.n
    size = arch.size
    jp = np.asarray(arch.joint_points, float) / size
    g = np.asarray(arch.centroids, float) / size
    w = np.asarray(arch.masses, float) / np.sum(arch.masses)
    d = 1.0 if direction == "l" else -1.0
    e = jp[:, 1] - jp[:, 0]
    L = np.hypot(e[:, 0], e[:, 1])
    u = e / L[:, None]
    nu = np.column_stack([u[:, 1], -u[:, 0]])
    m = n + 1
    nv = 3 * m + 1  # [N_0..N_n, T_0..T_n, m_0..m_n, lambda]

    def cross(p, v):
        return p[0] * v[1] - p[1] * v[0]

    def joint_terms(j, sign, row_fx, row_fy, row_mo):
        # +F_j (sign 1) or -F_j (sign -1); F_j = N nu + T u, moment P_in x F - m
        row_fx[j] += sign * nu[j, 0]
        row_fx[m + j] += sign * u[j, 0]
        row_fy[j] += sign * nu[j, 1]
        row_fy[m + j] += sign * u[j, 1]
        row_mo[j] += sign * cross(jp[j, 0], nu[j])
        row_mo[m + j] += sign * cross(jp[j, 0], u[j])
        row_mo[2 * m + j] -= sign

    A_eq, b_eq = [], []
    for i in range(n):
        fx, fy, mo = np.zeros(nv), np.zeros(nv), np.zeros(nv)
        joint_terms(i, 1.0, fx, fy, mo)
        joint_terms(i + 1, -1.0, fx, fy, mo)
        fx[-1] = d * w[i]
        mo[-1] = -d * w[i] * g[i, 1]
        A_eq += [fx, fy, mo]
        b_eq += [0.0, w[i], w[i] * g[i, 0]]
    A_ub, b_ub = [], []
    for j in range(m):
        for coef in ((0.0, 0.0, -1.0), (-L[j], 0.0, 1.0),
                     (-mu, 1.0, 0.0), (-mu, -1.0, 0.0)):
            row = np.zeros(nv)
            row[j], row[m + j], row[2 * m + j] = coef
            A_ub.append(row)
            b_ub.append(0.0)
    c = np.zeros(nv)
    c[-1] = -1.0
    res = linprog(c, A_ub=np.array(A_ub), b_ub=b_ub, A_eq=np.array(A_eq), b_eq=b_eq,
                  bounds=[(None, None)] * nv, method="highs")
    assert res.status == 0, res.message
    return res.x[-1]


def _tilted_polygon():
    from archrock.geometry import PolygonArch, as_polygon

    poly = as_polygon(nominal_arch(5.0, 160.0, 0.9, 8), 6)
    rng = np.random.default_rng(4)
    intr = [p.copy() for p in poly.intrados]
    extr = [p.copy() for p in poly.extrados]
    for j in range(1, 8):  # turn each inner joint about its middle
        a = rng.uniform(-0.12, 0.12)
        rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
        ends = [(intr, j - 1, -1), (extr, j - 1, -1), (intr, j, 0), (extr, j, 0)]
        c = 0.5 * (intr[j][0] + extr[j][0])
        for lines, i, k in ends:
            lines[i][k] = c + rot @ (lines[i][k] - c)
    return PolygonArch(tuple(intr), tuple(extr), 2000.0, "tilted joints")


@pytest.mark.parametrize("case", ["oppenheim", "irregular", "pointed", "pointed40", "loaded",
                                  "tilted"])
def test_independent_voussoir_by_voussoir_lp(case):
    arch = {
        "oppenheim": oppenheim_arch,
        "irregular": lambda: _irregular(9),
        "pointed": lambda: family_arch("pointed", 10.0, 8.0, 0.8, 8),
        # joints turning by 22.5 deg at the crown: the joint beside it needs the most friction
        "pointed40": lambda: family_arch("pointed", 10.0, 7.0, 1.0, 40),
        "loaded": lambda: Arch(np.full(7, math.radians(22.5)), np.full(7, 10.0), np.full(7, 1.5),
                               2000.0, "loaded", (Load(2, 5000.0, (-2.0, 11.0)),)),
        "tilted": _tilted_polygon,
    }[case]()
    need = friction.friction_needed(arch)
    for mu in (0.9 * min(need.values()), 0.75 * min(need.values()), 2.0):
        try:
            res = friction.friction_analysis(arch, mu)
        except CannotStandError:
            continue
        for d in ("l", "r"):
            assert res.direction(d).multiplier == pytest.approx(_voussoir_lp(arch, d, mu),
                                                                abs=1e-7)


def test_pointed_arch_needs_most_friction_beside_the_crown():
    a = family_arch("pointed", 10.0, 7.0, 1.0, 40)
    res = friction.friction_analysis(a, 0.6)
    assert res.l.friction_needed == pytest.approx(0.6556, abs=1e-4)
    assert res.l.sliding_governs and res.l.joints == (19,) and res.r.joints == (21,)
    assert res.l.multiplier == pytest.approx(0.226762, abs=1e-6)


# ---------------------------------------------------------------------------- outcomes and input
def test_squat_arch_no_mechanism_without_friction():
    """A squat arch no horizontal load can open (unbounded multiplier): no friction needed
    (None); low friction makes it slide at a finite multiplier; high friction leaves it
    unbounded (NoMechanismError, a physical outcome)."""
    from archrock.errors import NoMechanismError

    a = nominal_arch(10.0, 90.0, 6.0, 7)
    assert friction.friction_needed(a) == {"l": None, "r": None}
    res = friction.friction_analysis(a, 0.3)
    assert 0 < res.l.multiplier < 10 and res.l.sliding_governs
    assert res.l.ratios[list(res.l.joints)] == pytest.approx(0.3, rel=1e-6)
    assert res.l.multiplier == pytest.approx(_voussoir_lp(a, "l", 0.3), abs=1e-7)
    with pytest.raises(NoMechanismError, match="unbounded"):
        friction.friction_analysis(a, 100.0)


def test_an_arch_that_slides_under_its_own_weight_says_how_much_friction_it_needs():
    a = oppenheim_arch()
    with pytest.raises(CannotStandError, match=r"at least 0\.2063") as exc:
        friction.friction_analysis(a, 0.2)
    assert "friction 0.2" in str(exc.value)
    res = friction.friction_analysis(a, 0.2064)
    assert 0 <= res.k < 0.01


@pytest.mark.parametrize("mu", [0, -0.3, math.nan, math.inf, "x", None])
def test_friction_coefficient_is_checked(mu):
    with pytest.raises(ArchInputError, match="friction.*allowed a finite friction coefficient > 0"):
        friction.friction_analysis(oppenheim_arch(), mu)
    with pytest.raises(ArchInputError, match="friction"):
        friction.friction_minimum_thickness(oppenheim_arch(), mu)


def test_not_an_arch_and_a_surveyed_polygon():
    from archrock.geometry import as_polygon

    for f in (friction.friction_needed, lambda a: friction.friction_analysis(a, 0.5)):
        with pytest.raises(ArchInputError, match="arch"):
            f("not an arch")
    with pytest.raises(ArchInputError, match="thickness cannot be varied"):
        friction.friction_minimum_thickness(as_polygon(oppenheim_arch(), 5), 0.5)


def test_result_is_frozen_and_serialises():
    res = friction.friction_analysis(oppenheim_arch(), 0.45)
    d = json.loads(json.dumps(res.to_dict()))
    assert d["l"]["sliding_governs"] is True and d["l"]["joints"] == [7]
    assert len(d["l"]["ratios"]) == 8
    with pytest.raises(ValueError):
        res.l.ratios[0] = 1.0


# ---------------------------------------------------------------------------- command line
def _cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_friction_needed_always(capsys):
    code, out, _ = _cli(capsys, "limit", "--json")
    d = json.loads(out)
    assert code == 0
    assert d["friction_needed_l"] == pytest.approx(0.495132, abs=1e-6)
    assert d["friction_needed_r"] == pytest.approx(0.495132, abs=1e-6)
    assert "friction_k_l" not in d
    code, out, _ = _cli(capsys, "limit")
    assert "needs (largest |T|/N on its thrust line): M_l 0.4951, M_r 0.4951" in out


def test_cli_friction(capsys):
    code, out, _ = _cli(capsys, "limit", "--friction", "0.4", "--json")
    d = json.loads(out)
    api = friction.friction_analysis(oppenheim_arch(), 0.4)
    assert d["friction_k_l"] == pytest.approx(api.l.multiplier, abs=1e-12)
    assert d["friction_k_r"] == pytest.approx(api.r.multiplier, abs=1e-12)
    assert d["sliding_governs_l"] is True and d["friction_joints_l"] == [7]
    assert d["friction_joints_r"] == [0]
    assert d["friction_needed_l"] == pytest.approx(0.495132, abs=1e-6)
    assert d["k_l"] == pytest.approx(K_OPPENHEIM, abs=1e-12)  # unchanged
    code, out, _ = _cli(capsys, "limit", "--friction", "0.4")
    assert "M_l              0.2638           0.3700              yes  7 (0.4000)" in out


def test_cli_friction_limited_minimum_thickness(capsys):
    flags = ["limit", "--embrace", "180", "--thickness", "1.5", "--voussoirs", "30"]
    code, out, _ = _cli(capsys, *flags, "--friction", "0.37", "--min-thickness", "--json")
    assert code == 0
    d = json.loads(out)
    assert d["min_thickness"]["friction"] == 0.37
    api = friction.friction_minimum_thickness(nominal_arch(10.0, 180.0, 1.5, 30), 0.37)
    assert d["min_thickness"]["ratio_t_over_R"] == pytest.approx(api.ratio, rel=1e-12)
    code, out, err = _cli(capsys, *flags, "--friction", "0.3", "--min-thickness")
    assert code == 3 and "no thickness stands under its own weight with friction 0.3" in err


@pytest.mark.parametrize("value, says", [("0", "allowed > 0"), ("-1", "allowed > 0"),
                                         ("nan", "finite"), ("inf", "finite"), ("x", "number")])
def test_cli_friction_is_checked(capsys, value, says):
    code, _, err = _cli(capsys, "limit", "--friction", value)
    assert code == 2 and "--friction" in err and says in err


# ---------------------------------------------------------------------------- bounded searches
class _CountLPs:
    """Counts the linear programs archrock.statics.friction solves (its own reference to linprog); a
    search that runs away fails at 1000 programs instead of hanging the suite."""

    def __init__(self, monkeypatch):
        self.n = 0
        real = friction.linprog

        def counted(*args, **kwargs):
            self.n += 1
            if self.n > 1000:
                raise AssertionError("more than 1000 linear programs in one search")
            return real(*args, **kwargs)

        monkeypatch.setattr(friction, "linprog", counted)


def test_no_finite_friction_on_a_squat_segmental_arch(monkeypatch):
    """Oppenheim's arch with an embrace of 80 deg: at the frictionless collapse (k = 3.902) the
    thrust leaves a springing along the joint (N = 0, T = 0.288 W).  The former absolute
    tolerance (1e-10 on mu) never ended there (mu climbed to 1e7-1e15, whose ulp exceeds it);
    now each direction ends in 3 LPs with None and the reason "no finite friction"."""
    a = nominal_arch(10.0, 80.0, 1.5, 7)
    lps = _CountLPs(monkeypatch)
    need = friction.friction_needed(a)
    assert need == {"l": None, "r": None}
    assert lps.n <= 8
    for d, j in (("l", 0), ("r", 7)):
        why = need.reasons[d]
        assert why.startswith(friction.NO_FINITE_FRICTION)
        assert f"joint {j}" in why and "3.9020" in why and "> 1000" in why
    # with a real friction the arch slides at both springings, at a finite multiplier
    lps.n = 0
    res = friction.friction_analysis(a, 0.5)
    assert lps.n <= 20
    for d in ("l", "r"):
        fd = res.direction(d)
        assert fd.friction_needed is None and fd.friction_needed_reason.startswith(
            "no finite friction")
        assert fd.sliding_governs and fd.frictionless == pytest.approx(3.902013, abs=1e-6)
        assert fd.multiplier == pytest.approx(_voussoir_lp(a, d, 0.5), abs=1e-7)
        assert fd.joints == (0, 7)
    d = json.loads(json.dumps(res.to_dict()))
    assert d["l"]["friction_needed"] is None
    assert d["l"]["friction_needed_reason"].startswith("no finite friction")
    # even a huge friction coefficient does not give the frictionless multiplier
    assert friction.friction_analysis(a, 1e4).l.sliding_governs


def test_near_lift_off_friction_is_found_in_a_bounded_number_of_lps(monkeypatch):
    """A squat arch whose collapse needs a large but finite friction (a springing with a small
    normal force): the bisection ends in at most ~55 LPs per direction, to 1e-10 relative, and
    the value is where the friction multiplier drops."""
    a = nominal_arch(10.0, 85.2, 1.85, 17)
    lps = _CountLPs(monkeypatch)
    need = friction.friction_needed(a)
    assert lps.n <= 2 * 60
    assert need.reasons == {"l": None, "r": None}
    assert 5 < need["l"] < friction.MU_CAP
    assert need["r"] == pytest.approx(need["l"], rel=1e-8)  # a symmetric arch
    up = friction.friction_analysis(a, need["l"] * (1 + 1e-6)).l
    down = friction.friction_analysis(a, need["l"] * (1 - 1e-4)).l
    assert not up.sliding_governs and down.sliding_governs


def test_bisection_bound_raises_a_clear_error(monkeypatch):
    """The explicit bound on the bisection (never reached by the arithmetic: ~50 halvings from
    MU_CAP to the tolerances) turns into LimitExceededError, not an endless loop.  Under
    self-weight (lambda = 0) many states stand, so the least friction needs the bisection."""
    from archrock.errors import LimitExceededError

    monkeypatch.setattr(friction, "_MAX_BISECTIONS", 3)
    fs = friction._FrictionStatics(oppenheim_arch(), "l")
    with pytest.raises(LimitExceededError, match="did not reach its tolerance in 3"):
        fs.least_friction(0.0)


def test_least_friction_under_self_weight_to_a_relative_tolerance(monkeypatch):
    """The least friction with which Oppenheim's arch stands (lambda = 0, not a unique state:
    a full bisection), found from MU_CAP down in a bounded number of LPs, and just above it the
    arch stands with friction, just below it it slides (1e-8 relative either side)."""
    fs = friction._FrictionStatics(oppenheim_arch(), "l")
    lps = _CountLPs(monkeypatch)
    mu, x = fs.least_friction(0.0, None, friction.MU_CAP)
    assert lps.n <= 60
    assert mu == pytest.approx(0.2063, abs=1e-4)
    # the state found needs mu within the margin tolerance (1e-10 per W on the Coulomb rows)
    assert float(np.max(fs.ratios(x))) == pytest.approx(mu, rel=1e-8)
    assert friction.friction_analysis(oppenheim_arch(), mu * (1 + 1e-8)).k >= 0
    with pytest.raises(CannotStandError):
        friction.friction_analysis(oppenheim_arch(), mu * (1 - 1e-8))


def test_minimum_thickness_tolerance_is_checked():
    with pytest.raises(ArchInputError, match="tol.*0.5"):
        friction.friction_minimum_thickness(oppenheim_arch(), 0.5, tol=100)
    with pytest.raises(ArchInputError, match="tol"):
        friction.friction_minimum_thickness(oppenheim_arch(), 0.5, tol=0.0)


@pytest.mark.parametrize("seed", range(6))
def test_random_squat_arches_end_in_bounded_lps(monkeypatch, seed):
    """Squat arches (embrace 40-100 deg, t/R 0.05-0.3, 3-20 voussoirs), irregular or not:
    every friction function ends within its LP budget with a number or a reason."""
    rng = np.random.default_rng(100 + seed)
    a = nominal_arch(10.0, rng.uniform(40, 100), 10 * rng.uniform(0.05, 0.3),
                     int(rng.integers(3, 21)))
    if seed % 2:
        a = random_arch(a, seed=seed, spread_span=0.1, spread_thickness=0.1, spread_radius=0.05)
    lps = _CountLPs(monkeypatch)
    need = friction.friction_needed(a)
    assert lps.n <= 2 * 60
    for d in ("l", "r"):
        assert (need[d] is None) != (need.reasons[d] is None)
        assert need[d] is None or 0 <= need[d] <= friction.MU_CAP
    lps.n = 0
    try:
        friction.friction_analysis(a, 0.5)
    except (CannotStandError, NoMechanismError):
        pass
    assert lps.n <= 2 * 130
    lps.n = 0
    friction.friction_minimum_thickness(a, 0.5)
    assert lps.n <= 80


def test_cli_no_finite_friction(capsys):
    """`archrock limit --embrace 80` (once endless): null with a reason in JSON, "no finite
    friction" in the text."""
    code, out, _ = _cli(capsys, "limit", "--embrace", "80", "--friction", "0.5", "--json")
    d = json.loads(out)
    assert code == 0
    assert d["friction_needed_l"] is None and d["friction_needed_r"] is None
    assert d["friction_needed_reason_l"].startswith("no finite friction")
    assert d["friction_k_l"] == pytest.approx(2.957935, abs=1e-5)
    code, out, _ = _cli(capsys, "limit", "--embrace", "80")
    assert code == 0
    assert "M_l no finite friction, M_r no finite friction" in out
    code, out, _ = _cli(capsys, "limit", "--json")
    d = json.loads(out)
    assert d["friction_needed_reason_l"] is None
    assert d["friction_needed_l"] == pytest.approx(0.495132, abs=1e-6)
