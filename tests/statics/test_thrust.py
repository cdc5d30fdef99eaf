"""The thrust range under self-weight (archrock.statics.thrust, issue 20 part 1): the semicircle with
radial joints against its closed forms (Heyman 1995; Ochsendorf 2002, 2006), every arch against
an independent enumeration of three-hinge lines of thrust, mirror images, the scale law, the
minimum thickness (where the range closes), the JSON/text reports and the command line."""

import json
import math
from itertools import combinations

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from archrock.statics import limit
from archrock.cli import main
from archrock.errors import CannotStandError
from archrock.geometry import Arch, Load, family_arch, nominal_arch, oppenheim_arch, random_arch
from archrock.statics.thrust import ThrustRange, thrust_range
from archrock.units import G

# Oppenheim's arch (R = 10 m, 157.5 deg, t = 1.5 m, 7 voussoirs, 2000 kg/m^3) [N/m]
OPPENHEIM_H_MIN = 156766.4856
OPPENHEIM_H_MAX = 264357.3582


# ---------------------------------------------------------------------------- closed forms
# Semicircle of centreline radius R = 1 and thickness t, radial joints, rho g = 1 per unit area:
# a = 1 - t/2 (intrados), b = 1 + t/2 (extrados); the part from the crown to the joint at beta
# from the crown is an annular sector of weight W(beta) = t beta whose first moment about the
# vertical axis is S(beta) = (b^3 - a^3)/3 (1 - cos beta).  By symmetry the crown transmits a
# horizontal force H.
#
# Minimum thrust (supports spreading): the line of thrust touches the crown's extrados (height b)
# and the intrados at the haunch; moments about the intrados point (a sin beta, a cos beta) of the
# crown part give H (b - a cos beta) = W a sin beta - S, and H_min = max over beta.
#
# Maximum thrust (supports closing): the line touches the springing's extrados (b, 0) and the
# intrados at beta (the crown, beta = 0, on thick rings): moments of the half arch about (b, 0),
# H y_c = M_s = W(pi/2) b - S(pi/2), and of the crown part about the intrados point at beta,
# H (y_c - a cos beta) >= M(beta) = W a sin beta - S (the line passes outside the intrados), give
# H a cos beta <= M_s - M(beta): H_max = min over beta of (M_s - M(beta)) / (a cos beta).


def _sector(beta, t):
    a, b = 1 - t / 2, 1 + t / 2
    return a, b, t * beta, (b**3 - a**3) / 3 * (1 - np.cos(beta))


def h_min_at(beta, t):
    a, b, w, s = _sector(beta, t)
    return (w * a * np.sin(beta) - s) / (b - a * np.cos(beta))


def h_max_at(beta, t):
    a, b, w, s = _sector(beta, t)
    _, _, w2, s2 = _sector(math.pi / 2, t)
    return (w2 * b - s2 - (w * a * np.sin(beta) - s)) / (a * np.cos(beta))


def _extremum(f, sign):
    """(value, beta) of the extremum of sign * f over [0, pi/2): grid, then Brent."""
    grid = np.linspace(1e-9, math.pi / 2 - 1e-6, 20001)
    k = int(np.argmax(sign * f(grid)))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    r = minimize_scalar(lambda x: -sign * f(x), bounds=(lo, hi), method="bounded",
                        options={"xatol": 1e-12})
    cand = [(sign * f(grid[0]), grid[0]), (-r.fun, r.x)]
    best = max(cand)
    return sign * best[0], best[1]


def closed_form(t):
    """(H_min, beta_min, H_max, beta_max) / (rho g R^2), angles from the crown [rad]."""
    hmin, bmin = _extremum(lambda x: h_min_at(x, t), +1)
    hmax, bmax = _extremum(lambda x: h_max_at(x, t), -1)
    return hmin, bmin, hmax, bmax


def closed_form_at_joints(t, n=180):
    """The same extrema over the joints of the n-voussoir semicircle only (its weights are the
    exact sectors between joints, so this is the discrete arch's own closed form)."""
    beta = np.arange(1, n // 2 + 1) * (math.pi / n)
    hmin = float(np.max(h_min_at(beta, t)))
    beta0 = np.arange(0, n // 2) * (math.pi / n)
    hmax = float(np.min(np.concatenate([h_max_at(beta0[1:], t), [h_max_at(1e-300, t)]])))
    return hmin, hmax


def _loaded():
    """Oppenheim's arch with 8 t/m on its third voussoir, off its mass centre (asymmetric)."""
    a = oppenheim_arch()
    return Arch(a.spans, a.radii, a.thicknesses, a.density, name="loaded",
                loads=(Load(2, 8000.0, (-3.0, 10.0)),))


def _semicircle(t_over_r, n=180, radius=1.0):
    return nominal_arch(radius=radius, embrace_deg=180.0, thickness=t_over_r * radius,
                        voussoirs=n)


def _nondim(arch, H, radius=1.0):
    return H / (arch.density * G * radius**2)


def test_closed_form_matches_the_issue():
    # issue 20: at t/R = 0.15 the minimum is 0.0829 with the haunch hinge about 57.8 deg
    hmin, bmin, hmax, bmax = closed_form(0.15)
    assert hmin == pytest.approx(0.0829, abs=5e-5)
    assert math.degrees(bmin) == pytest.approx(57.8, abs=0.05)
    # the maximum touches the intrados at 43.9 deg from the crown, the extrados at the springing
    assert hmax == pytest.approx(0.106960, abs=1e-6)
    assert math.degrees(bmax) == pytest.approx(43.90, abs=0.01)
    # at t/R = 0.30 it touches the crown's intrados: H_max = M_s / a
    a, b = 0.85, 1.15
    hmax30 = closed_form(0.30)[2]
    assert hmax30 == pytest.approx((math.pi / 2 * 0.3 * b - (b**3 - a**3) / 3) / a, rel=1e-12)


@pytest.mark.parametrize("t", [0.12, 0.15, 0.20, 0.30])
def test_semicircle_against_closed_form(t):
    arch = _semicircle(t)
    tr = thrust_range(arch)
    lp_min, lp_max = _nondim(arch, tr.thrust_min), _nondim(arch, tr.thrust_max)
    # the discrete arch's own closed form (hinges at its joints): the LP to rounding
    d_min, d_max = closed_form_at_joints(t)
    assert lp_min == pytest.approx(d_min, rel=1e-9)
    assert lp_max == pytest.approx(d_max, rel=1e-9)
    # the discrete arch's value agrees with it to 2e-14 (measured); with the continuous closed
    # form (hinges anywhere) it agrees to 4.7e-5, 1.5e-5, 5.2e-5, 3.9e-5 (H_min, t/R = 0.12,
    # 0.15, 0.20, 0.30) and 4.1e-5, 1.1e-6, 2.0e-6, 0 (H_max) measured: with a joint every
    # degree the line of thrust has fewer places to touch, so the range is a little narrower
    hmin, bmin, hmax, bmax = closed_form(t)
    assert -1e-12 <= (hmin - lp_min) / hmin < 1e-4
    assert -1e-12 <= (lp_max - hmax) / hmax < 1e-4
    # hinges: min thrust at the crown's extrados and the intrados at +-beta_min (to a joint)
    joints = {(h.joint, h.edge) for h in tr.hinges_min}
    crown = 90
    k = [j for j, e in joints if e == "intrados" and j < crown]
    assert (crown, "extrados") in joints and len(k) == 1
    assert joints == {(crown, "extrados"), (k[0], "intrados"), (180 - k[0], "intrados")}
    assert abs((crown - k[0]) - math.degrees(bmin)) <= 1.0
    # max thrust at the springings' extrados and the intrados at +-beta_max (the crown at 0.30)
    joints = {(h.joint, h.edge) for h in tr.hinges_max}
    assert {(0, "extrados"), (180, "extrados")} <= joints
    inner = sorted(j for j, e in joints if e == "intrados")
    assert inner and all(abs(abs(crown - j) - math.degrees(bmax)) <= 1.0 for j in inner)
    assert len(joints) == 2 + len(inner) and inner[0] + inner[-1] == 180
    # the hinge points lie on the intrados (radius a) and extrados (radius b)
    for h, p in zip(tr.hinges_min + tr.hinges_max, np.vstack([tr.points_min, tr.points_max])):
        r = 1 - t / 2 if h.edge == "intrados" else 1 + t / 2
        assert math.hypot(*p) == pytest.approx(r, abs=1e-7)


def test_minimum_thickness_closes_the_range():
    # below t/R = 0.1075 the semicircle cannot stand; at its minimum thickness the least and the
    # greatest thrust meet (one line of thrust fits), above it they part
    arch = _semicircle(0.15, n=36)
    mt = limit.minimum_thickness(arch, tol=1e-10)
    at = thrust_range(arch.with_thickness_factor(mt.factor * (1 + 1e-8)))
    assert (at.thrust_max - at.thrust_min) / at.thrust_min < 1e-5
    # the closed form gives the same least thickness: H_min(t) = H_max(t) at t = 0.1075 (36
    # joints: 0.1070), bracketed here
    lo, hi = closed_form(0.105), closed_form(0.110)
    assert lo[0] > lo[2] and hi[0] < hi[2]
    with pytest.raises(CannotStandError):
        thrust_range(_semicircle(0.10, n=36))


# ---------------------------------------------------------------------------- three-hinge lines
def _three_hinge_range(arch, tol=1e-9):
    """Least and greatest H [N/m] over the lines of thrust through any three joint ends that lie
    inside every contact segment, in compression: the vertices of the static program, by plain
    equilibrium written here (not archrock.statics.limit's program).  Left-support force (H, V) with
    moment m0 about the origin; across joint j the resultant is (H, V - C_j) with moment
    m0 - S_j (C_j, S_j: the weight of voussoirs 0..j-1 and its moment about the y axis).
    A point p on its line of action: p_x (V - C_j) - p_y H = m0 - S_j."""
    w = G * np.asarray(arch.masses, float)
    xg = np.asarray(arch.centroids, float)[:, 0]
    C = np.concatenate([[0.0], np.cumsum(w)])
    S = np.concatenate([[0.0], np.cumsum(w * xg)])
    jp = np.asarray(arch.joint_points, float)  # (n+1, edge, xy)
    ends = [(j, e) for e in (0, 1) for j in range(arch.n + 1)]
    best = [math.inf, -math.inf]
    for trio in combinations(ends, 3):
        A = np.array([[-jp[j, e, 1], jp[j, e, 0], -1.0] for j, e in trio])
        rhs = np.array([jp[j, e, 0] * C[j] - S[j] for j, e in trio])
        if abs(np.linalg.det(A)) < 1e-12 * np.max(np.abs(A)) ** 2:
            continue
        H, V, m0 = np.linalg.solve(A, rhs)
        F = np.column_stack([np.full(C.size, H), V - C])
        m = m0 - S
        pin, pout = jp[:, 0], jp[:, 1]
        e = pout - pin
        normal = F[:, 0] * e[:, 1] - F[:, 1] * e[:, 0]  # F . (e turned clockwise)
        if not np.all(normal > 0):
            continue
        # the crossing pin + s e: (pin + s e) x F = m
        s = (m - (pin[:, 0] * F[:, 1] - pin[:, 1] * F[:, 0])) / -normal
        if np.all(s >= -tol) and np.all(s <= 1 + tol):
            best = [min(best[0], H), max(best[1], H)]
    return best


@pytest.mark.parametrize("make", [
    oppenheim_arch,
    lambda: random_arch(nominal_arch(10.0, 157.5, 1.5, 9), seed=3, spread_span=0.15,
                        spread_thickness=0.15, spread_radius=0.08),
    lambda: family_arch("pointed", 10.0, 7.0, 1.0, 10),
    lambda: nominal_arch(5.0, 180.0, 0.9, 20),
    lambda: _loaded(),
], ids=["oppenheim", "irregular", "pointed", "semicircle-20", "loaded"])
def test_lp_against_three_hinge_enumeration(make):
    arch = make()
    tr = thrust_range(arch)
    lo, hi = _three_hinge_range(arch)
    assert tr.thrust_min == pytest.approx(lo, rel=1e-9)
    assert tr.thrust_max == pytest.approx(hi, rel=1e-9)
    assert 0 < tr.thrust_min < tr.thrust_max


# ---------------------------------------------------------------------------- Oppenheim
def test_oppenheim_thrust_range():
    arch = oppenheim_arch()
    tr = thrust_range(arch)
    assert tr.thrust_min == pytest.approx(OPPENHEIM_H_MIN, rel=1e-9)
    assert tr.thrust_max == pytest.approx(OPPENHEIM_H_MAX, rel=1e-9)
    assert tr.weight == pytest.approx(G * 2000.0 * math.radians(157.5) * 10.0 * 1.5, rel=1e-12)
    # spreading: the crown voussoir's joints open at the extrados, the haunches at the intrados;
    # closing: the reverse, with the springings at the extrados
    assert [(h.joint, h.edge) for h in tr.hinges_min] == [
        (1, "intrados"), (3, "extrados"), (4, "extrados"), (6, "intrados")]
    assert [(h.joint, h.edge) for h in tr.hinges_max] == [
        (0, "extrados"), (3, "intrados"), (4, "intrados"), (7, "extrados")]
    for hinges, pts in ((tr.hinges_min, tr.points_min), (tr.hinges_max, tr.points_max)):
        for h, p in zip(hinges, pts):
            np.testing.assert_allclose(p, arch.joint_point(h.joint, h.edge), atol=1e-6)
    # the lines of thrust carry the weight: vertical reactions W/2 each, H across every joint
    for line, H in ((tr.line_min, tr.thrust_min), (tr.line_max, tr.thrust_max)):
        assert line.multiplier == 0.0 and line.direction == "l"
        np.testing.assert_allclose(line.forces[:, 0] * tr.weight, H, rtol=1e-12)
        assert line.forces[0, 1] == pytest.approx(0.5, abs=1e-9)
        assert np.all((line.fractions >= -1e-9) & (line.fractions <= 1 + 1e-9))
    d = tr.to_dict()
    assert d["thrust_min"]["H"] == pytest.approx(OPPENHEIM_H_MIN, rel=1e-9)
    assert d["thrust_max"]["hinges"][0] == {"joint": 0, "edge": "extrados"}
    assert len(d["thrust_min"]["points"]) == 4 and len(d["thrust_min"]["crossings"]) == 8
    assert json.loads(json.dumps(d)) == d


@pytest.mark.parametrize("make", [
    oppenheim_arch,
    lambda: random_arch(nominal_arch(10.0, 157.5, 1.5, 9), seed=5, spread_span=0.15,
                        spread_thickness=0.15, spread_radius=0.08),
    lambda: _loaded(),
], ids=["oppenheim", "irregular", "loaded"])
def test_mirror(make):
    arch = make()
    tr, mr = thrust_range(arch), thrust_range(arch.mirrored())
    assert mr.thrust_min == pytest.approx(tr.thrust_min, rel=1e-10)
    assert mr.thrust_max == pytest.approx(tr.thrust_max, rel=1e-10)
    n = arch.n
    for a, b in ((tr.hinges_min, mr.hinges_min), (tr.hinges_max, mr.hinges_max)):
        assert {(n - h.joint, h.edge) for h in a} == {(h.joint, h.edge) for h in b}


@pytest.mark.parametrize("f", [1e-3, 0.37, 1.0, 25.0, 1e3])
def test_scale_law(f):
    # fixed density: weights scale with f^2 and the lines of thrust with f, so H with f^2
    arch = random_arch(nominal_arch(10.0, 157.5, 1.5, 9), seed=2)
    base = thrust_range(arch)
    tr = thrust_range(arch.scaled(f))
    assert tr.thrust_min / f**2 == pytest.approx(base.thrust_min, rel=1e-9)
    assert tr.thrust_max / f**2 == pytest.approx(base.thrust_max, rel=1e-9)
    assert tr.hinges_min == base.hinges_min and tr.hinges_max == base.hinges_max
    np.testing.assert_allclose(tr.points_min / f, base.points_min, rtol=0, atol=1e-9 * 10)


def test_flat_arch_has_no_greatest_thrust():
    # a flat arch wedged between its springings carries any thrust (as limit analysis finds no
    # mechanism at 60 deg of embrace and below)
    tr = thrust_range(nominal_arch(10.0, 40.0, 1.5, 7))
    assert tr.thrust_max == math.inf and tr.line_max is None and tr.hinges_max == ()
    assert 0 < tr.thrust_min < math.inf
    d = tr.to_dict()["thrust_max"]
    assert d["H"] is None and d["bounded"] is False and d["hinges"] == []


def test_result_is_frozen():
    tr = thrust_range(oppenheim_arch())
    assert isinstance(tr, ThrustRange)
    with pytest.raises(Exception):
        tr.thrust_min = 0.0
    with pytest.raises(ValueError):
        tr.points_min[0, 0] = 0.0


# ---------------------------------------------------------------------------- command line
def _cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_thrust_range(capsys):
    code, out, _ = _cli(capsys, "limit", "--thrust-range", "--json")
    assert code == 0
    d = json.loads(out)
    assert d["thrust_min"]["H"] == pytest.approx(OPPENHEIM_H_MIN, rel=1e-9)
    assert d["thrust_max"]["H"] == pytest.approx(OPPENHEIM_H_MAX, rel=1e-9)
    assert d["thrust_min"]["hinges"] == [{"joint": 1, "edge": "intrados"},
                                         {"joint": 3, "edge": "extrados"},
                                         {"joint": 4, "edge": "extrados"},
                                         {"joint": 6, "edge": "intrados"}]
    assert len(d["thrust_max"]["points"]) == 4
    assert d["k_l"] == pytest.approx(0.3700097380218772, abs=1e-12)  # unchanged
    code, out, _ = _cli(capsys, "limit", "--thrust-range")
    assert code == 0
    assert ("thrust range under self-weight: H_min = 156.7665 kN/m (hinges 1 intrados, "
            "3 extrados, 4 extrados, 6 intrados), H_max = 264.3574 kN/m (hinges 0 extrados, "
            "3 intrados, 4 intrados, 7 extrados)") in out
    code, out, _ = _cli(capsys, "limit", "--json")
    assert "thrust_min" not in json.loads(out)
