"""Four-link model, impacts and responses of any arch shape (VoussoirArch): a circular arch written
as polygons gives the circular results, loads enter the coefficients, Housner's rocking frame as
a polygon arch, drawing displaced polygons, the circular-only batch path.

Limit analysis of a PolygonArch comes with another branch; until then the polygon models here
are built from the circular arch's hinges (the same joints under ``as_polygon``), with the
multipliers of those mechanisms on the polygon arch (virtual work, ``static_multiplier``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archrock import geometry, groundmotion as gm
from archrock.statics import limit
from archrock.errors import ArchInputError
from archrock.geometry import Load, PolygonArch, as_polygon
from archrock.dynamics.impact import impact_law, least_loss_mechanism
from archrock.statics.limit import Hinge, LimitResult, Mechanism
from archrock.dynamics.fourlink import (GEO_OK, GEO_SIZE, coefficients, four_link, mechanism_geo,
                                        rates)
from archrock.dynamics.response import prepare, respond, time_scale

G = 9.81
PHIS = np.linspace(0.0, 0.12, 7)  # past Oppenheim's unstable rotation (0.069 rad)


@pytest.fixture(scope="module")
def opp(oppenheim):
    return oppenheim.arch, oppenheim.limit, oppenheim.left, oppenheim.right


def polygon_limit(poly, circular_limit) -> LimitResult:
    """A LimitResult for ``poly`` with the circular arch's hinges (same joints) and their own
    multipliers on ``poly`` (no thrust lines): what limit_analysis(poly) will give once it
    handles polygons, up to the discretisation."""
    mechs = [Mechanism(m.direction, m.hinges, abs(four_link(poly, m).static_multiplier()))
             for m in (circular_limit.mechanism_l, circular_limit.mechanism_r)]
    return LimitResult(poly, mechs[0].multiplier, mechs[1].multiplier, mechs[0], mechs[1], None,
                       None, method="hinges of the circular arch (tests)")


def _rel(a, b) -> float:
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def _coefficient_error(fa, fb) -> float:
    return max(_rel(fa.coefficients(p), fb.coefficients(p)) for p in PHIS)


# ------------------------------------------------------------------------- circular: unchanged
@pytest.mark.parametrize("seed", [None, 0, 7])
def test_circular_joint_points_are_the_old_numbers(seed):
    """four_link reads arch.joint_points; on a circular arch they are the r cos(psi), r sin(psi)
    it computed before, so every model (and every 0.1.0 result) is unchanged to the bit."""
    arch = geometry.oppenheim_arch() if seed is None else geometry.random_arch(seed=seed)
    radii = np.column_stack([arch.contact_inner, arch.contact_outer])
    px = radii * np.cos(arch.joint_angles)[:, None]
    py = radii * np.sin(arch.joint_angles)[:, None]
    assert np.array_equal(arch.joint_points[:, :, 0], px)
    assert np.array_equal(arch.joint_points[:, :, 1], py)
    lim = limit.limit_analysis(arch, verify=False)
    for m in (lim.mechanism_l, lim.mechanism_r):
        hinges = sorted(m.hinges, key=lambda h: h.joint)
        geo = np.empty(GEO_SIZE)
        code = mechanism_geo(px, py, arch.masses, np.ascontiguousarray(arch.centroids),
                             arch.inertias, np.array([h.joint for h in hinges], dtype=np.int64),
                             np.array([limit.EDGES.index(h.edge) for h in hinges], dtype=np.int64),
                             m.direction == "r", geo)
        assert code == GEO_OK and np.array_equal(four_link(arch, m).geo, geo)
    assert time_scale(arch) == math.sqrt(float(np.mean(arch.radii)) / G)


# ------------------------------------------------------------------------- polygon = circular
def test_polygon_four_link_equals_circular_and_converges(opp):
    """Oppenheim's arch as polygons: geometry vector and M, L, F, P at several rotations within
    1e-4 (relative) at 40 points per arc, the error falling as 1/points^2."""
    arch, lim, ml, mr = opp
    errors = []
    for pts in (20, 40, 80):
        poly = as_polygon(arch, pts)
        err = 0.0
        for circ, m in ((ml, lim.mechanism_l), (mr, lim.mechanism_r)):
            fl = four_link(poly, m)
            assert fl.arch is poly and fl.link_voussoirs == circ.link_voussoirs
            assert fl.sign == circ.sign
            scale = np.maximum(np.abs(circ.geo), 1.0)  # coordinates near 0: relative to 1 m
            err = max(err, float(np.max(np.abs(fl.geo - circ.geo) / scale)),
                      _coefficient_error(fl, circ))
            assert fl.phi_unstable == pytest.approx(circ.phi_unstable, rel=10 * err)
        errors.append(err)
    assert errors[1] < 1e-4
    assert errors[1] < errors[0] / 3 and errors[2] < errors[1] / 3  # second order


def test_polygon_impact_laws_equal_circular(opp):
    arch, lim, ml, mr = opp
    poly = as_polygon(arch, 40)
    pl, pr = four_link(poly, lim.mechanism_l), four_link(poly, lim.mechanism_r)
    for model, cv in (("paper", 0.87538), ("momentum", 0.64496)):
        circ, law = impact_law(ml, mr, model), impact_law(pl, pr, model)
        # the 5 decimals quoted (0.87538, 0.64496): solutions of small linear systems
        assert circ.l_to_r == pytest.approx(cv, abs=5e-6)
        for name in ("l_to_r", "r_to_l", "energy_l_to_r", "energy_r_to_l"):
            assert getattr(law, name) == pytest.approx(getattr(circ, name), rel=1e-4)
    # the least-loss choice: the same mechanism, the same kinetic-energy ratio
    a, b = least_loss_mechanism(ml, mr), least_loss_mechanism(pl, pr)
    assert a.mechanism.hinges == b.mechanism.hinges and a.candidates == b.candidates
    assert b.energy_ratio == pytest.approx(a.energy_ratio, rel=1e-4)


@pytest.mark.parametrize("model,impacts,peak", [
    ("paper", (0.6012, 2.2294, 3.3706), 0.0372),
    ("momentum", (0.6012, 1.4445, 1.9218), 0.0147),
    ("least-loss", (0.6012, 1.3854, 1.9648), 0.0284)])
def test_polygon_response_matches_the_papers_pulse(opp, model, impacts, peak):
    """The paper's pulse on Oppenheim's arch as polygons (40 points per arc): impacts within
    1e-3 s and the peak within 1e-4 rad of the circular arch's."""
    arch, lim, _, _ = opp
    poly = as_polygon(arch, 40)
    motion = gm.oppenheim_pulse(-1.0, 0.2)
    circ = respond(prepare(arch, model, limit=lim), motion, t_end=4.0)
    m = prepare(poly, model, limit=polygon_limit(poly, lim))
    assert m.arch is poly and m.labels == prepare(arch, model, limit=lim).labels
    r = respond(m, motion, t_end=4.0)
    assert r.status == circ.status == "rest"
    assert circ.impacts[:3] == pytest.approx(impacts, abs=1e-4)
    assert r.impacts[:3] == pytest.approx(circ.impacts[:3], abs=1e-3)
    assert r.peak == pytest.approx(circ.peak, abs=1e-4) and r.peak == pytest.approx(peak, abs=1e-4)
    assert len(r.impacts) == len(circ.impacts)


def _polygon_limit_analysis_works() -> bool:
    try:
        limit.limit_analysis(as_polygon(geometry.oppenheim_arch(), 8), verify=False)
    except (ArchInputError, TypeError, AttributeError, NotImplementedError):
        return False
    return True


@pytest.mark.skipif(not _polygon_limit_analysis_works(),
                    reason="limit_analysis of a PolygonArch arrives with the limit-analysis branch; "
                           "run after the merge")
def test_polygon_end_to_end_after_the_merge(opp):
    """prepare(polygon) with its own limit analysis: the circular hinges and the paper's pulse."""
    arch, lim, _, _ = opp
    poly = as_polygon(arch, 40)
    m = prepare(poly, "paper")
    assert m.labels == prepare(arch, "paper", limit=lim).labels
    assert m.k_l == pytest.approx(lim.k_l, rel=1e-3)
    r = respond(m, gm.oppenheim_pulse(-1.0, 0.2), t_end=4.0)
    assert r.impacts[:3] == pytest.approx([0.6012, 2.2294, 3.3706], abs=1e-3)
    assert r.peak == pytest.approx(0.0372, abs=1e-4)


def test_prepare_refuses_the_limit_of_another_arch(opp):
    arch, lim, _, _ = opp
    poly = as_polygon(arch, 40)
    with pytest.raises(ArchInputError, match="another arch"):
        prepare(poly, "paper", limit=lim)
    with pytest.raises(ArchInputError, match="VoussoirArch"):
        prepare("arch.json", "paper")
    with pytest.raises(ArchInputError, match="VoussoirArch"):
        four_link(None, lim.mechanism_l)
    # the same geometry in another object is this arch
    assert prepare(geometry.oppenheim_arch(), "paper", limit=lim).k_l == lim.k_l


# ------------------------------------------------------------------------- loads
def _independent_m_f_p(fl, arch):
    """M(0), F(0), P(0) summed over the bare voussoirs and their load points separately, each
    moving with its link (rates from the loop closure): shares no mass bookkeeping with
    four_link, which lumps every voussoir with its loads."""
    t = rates(0.0, fl.geo)[:3]
    (ax, ay), (bx, by), _, (dx, dy) = fl.points
    refs = ((ax, ay), (bx, by), (dx, dy))
    vb = t[0] * np.array([-(by - ay), bx - ax])
    bodies = []  # (mass, point, own inertia, link)
    for k, idx in enumerate(fl.link_voussoirs):
        for i in idx:
            bodies.append((arch.density * arch.areas[i], arch.area_centroids[i],
                           arch.density * arch.area_polar[i], k))
            bodies += [(ld.mass, np.array(ld.at), 0.0, k) for ld in arch.loads if ld.voussoir == i]
    M = F = P = 0.0
    for m, x, inertia, k in bodies:
        r = x - np.array(refs[k])
        v = t[k] * np.array([-r[1], r[0]]) + (vb if k == 1 else 0.0)
        M += m * (v @ v) + inertia * t[k] ** 2
        F += m * v[1]
        P -= m * v[0]
    return M, F, P


def _loaded(arch, loads):
    if isinstance(arch, PolygonArch):
        return PolygonArch(arch.intrados, arch.extrados, arch.density, arch.name, loads)
    return geometry.Arch(arch.spans, arch.radii, arch.thicknesses, arch.density, arch.name, loads)


@pytest.mark.parametrize("polygon", [False, True])
def test_loads_enter_the_four_link_coefficients(opp, polygon):
    arch, lim, _, _ = opp
    base = as_polygon(arch, 40) if polygon else arch
    loads = (Load(3, 4000.0, (0.4, 11.2)), Load(1, 900.0, (-6.5, 7.0)), Load(5, 300.0, (6.0, 8.5)))
    loaded = _loaded(base, loads)
    for m in (lim.mechanism_l, lim.mechanism_r):
        fl, bare = four_link(loaded, m), four_link(base, m)
        M, _, F, P = fl.coefficients(0.0)
        assert (M, F, P) == pytest.approx(_independent_m_f_p(fl, loaded), rel=1e-12)
        assert not np.isclose(M, bare.coefficients(0.0)[0], rtol=1e-3)
        assert fl.link_masses.sum() == pytest.approx(bare.link_masses.sum() + 5200.0, rel=1e-14)
    # the impact laws see them too (momentum: the voussoirs' masses and inertias with loads)
    ll = [four_link(loaded, m) for m in (lim.mechanism_l, lim.mechanism_r)]
    bb = [four_link(base, m) for m in (lim.mechanism_l, lim.mechanism_r)]
    assert abs(impact_law(*ll, "momentum").l_to_r - impact_law(*bb, "momentum").l_to_r) > 1e-3


@pytest.mark.parametrize("polygon", [False, True])
def test_zero_mass_load_changes_nothing(opp, polygon):
    arch, lim, _, _ = opp
    base = as_polygon(arch, 20) if polygon else arch
    loaded = _loaded(base, (Load(2, 0.0, (-3.0, 9.0)),))
    for m in (lim.mechanism_l, lim.mechanism_r):
        assert np.array_equal(four_link(loaded, m).geo, four_link(base, m).geo)
    pair = lambda a: [four_link(a, m) for m in (lim.mechanism_l, lim.mechanism_r)]  # noqa: E731
    for model in ("paper", "momentum"):
        assert impact_law(*pair(loaded), model) == impact_law(*pair(base), model)


def test_load_at_a_centroid_is_a_heavier_voussoir(opp):
    """A point mass f m_i at voussoir i's centroid: the voussoir of the same shape f + 1 times
    denser (built with the compiled core), less the point mass's missing own inertia."""
    arch, lim, _, _ = opp
    i, f = 2, 0.75
    loaded = _loaded(arch, (Load(i, f * arch.masses[i], tuple(arch.centroids[i])),))
    mass, inert = arch.masses.copy(), arch.inertias.copy()
    mass[i] *= 1 + f
    inert[i] *= 1 + f
    pts = arch.joint_points
    for m in (lim.mechanism_l, lim.mechanism_r):
        fl = four_link(loaded, m)
        hinges = sorted(m.hinges, key=lambda h: h.joint)
        geo = np.empty(GEO_SIZE)
        assert mechanism_geo(np.ascontiguousarray(pts[:, :, 0]), np.ascontiguousarray(pts[:, :, 1]),
                             mass, np.ascontiguousarray(arch.centroids), inert,
                             np.array([h.joint for h in hinges], dtype=np.int64),
                             np.array([limit.EDGES.index(h.edge) for h in hinges], dtype=np.int64),
                             m.direction == "r", geo) == GEO_OK
        link = next(k for k, idx in enumerate(fl.link_voussoirs) if i in idx)
        for phi in PHIS:
            M, L, F, P = fl.coefficients(phi)
            Mh, Lh, Fh, Ph = coefficients(phi, geo)
            t1, t2, t3, t2d, t3d, _ = rates(phi, geo)
            w, wd = (t1, t2, t3)[link], (0.0, t2d, t3d)[link]
            assert (F, P) == pytest.approx((Fh, Ph), rel=1e-12)
            assert M == pytest.approx(Mh - f * arch.inertias[i] * w * w, rel=1e-12)
            assert L == pytest.approx(Lh - f * arch.inertias[i] * w * wd, rel=1e-9, abs=1e-12 * M)
        _, _, F0, P0 = coefficients(0.0, geo)
        assert fl.static_multiplier() == pytest.approx(F0 / P0, rel=1e-12)


# ------------------------------------------------------------------------- Housner's frame


# M_l sways right: the columns rock on their bottom-right corners, hinged at their top-left
# corners; M_r is its mirror image
FRAME_L = Mechanism("l", (Hinge(0, "intrados"), Hinge(1, "extrados"), Hinge(2, "intrados"),
                          Hinge(3, "extrados")), math.nan)
FRAME_R = Mechanism("r", (Hinge(0, "extrados"), Hinge(1, "intrados"), Hinge(2, "extrados"),
                          Hinge(3, "intrados")), math.nan)


@pytest.mark.parametrize("b,h,depth", [(0.25, 1.0, 0.3), (0.5, 1.5, 0.05), (0.2, 2.5, 0.6),
                                       (0.3, 1.2, 1e-6)])
def test_rocking_frame_is_housners_block(b, h, depth, rocking_frame):
    """The frame's beam translates, so (gamma = beam mass / both columns' mass)
    M = 8/3 m R^2 (1 + 3 gamma), F = 2 m R (1 + 2 gamma) sin(alpha - phi), L = 0 and
    p^2 = 3 g / (4 R) (1 + 2 gamma) / (1 + 3 gamma): Housner's block at gamma = 0."""
    frame = rocking_frame(b, h, depth)
    m = frame.masses[0]
    gamma = frame.masses[1] / (2 * m)
    R, alpha = math.hypot(b, h), math.atan2(b, h)
    for mech in (FRAME_L, FRAME_R):
        fl = four_link(frame, mech)
        assert abs(fl.static_multiplier()) == pytest.approx(math.tan(alpha), rel=1e-9)
        assert fl.phi_unstable == pytest.approx(alpha, rel=1e-9)
        for phi in np.linspace(0.0, 1.5 * alpha, 7):
            M, L, F, P = fl.coefficients(phi)
            assert M == pytest.approx(8 / 3 * m * R * R * (1 + 3 * gamma), rel=1e-9)
            assert abs(L) < 1e-9 * M
            s = 2 * m * R * (1 + 2 * gamma)
            assert F == pytest.approx(s * math.sin(alpha - phi), abs=1e-9 * s)
            assert abs(P) == pytest.approx(s * math.cos(alpha - phi), rel=1e-9)
            if abs(alpha - phi) > 1e-3:
                p2 = G * F / (M * math.sin(alpha - phi))
                assert p2 == pytest.approx(3 * G / (4 * R) * (1 + 2 * gamma) / (1 + 3 * gamma),
                                           rel=1e-9)
    # momentum law: Makris & Vassiliou's frame, Housner's 1 - 1.5 sin^2(alpha) at gamma = 0
    law = impact_law(four_link(frame, FRAME_L), four_link(frame, FRAME_R), "momentum")
    c = (1 - 1.5 * math.sin(alpha) ** 2 + 3 * gamma * math.cos(2 * alpha)) / (1 + 3 * gamma)
    assert law.l_to_r == pytest.approx(c, rel=1e-9) and law.r_to_l == pytest.approx(c, rel=1e-9)
    if depth < 1e-3:
        assert law.l_to_r == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, abs=1e-5)


def test_rocking_frame_response(rocking_frame):
    """The frame as a DynamicModel (k = tan(alpha) both ways) rocks under a pulse and comes to
    rest, every impact keeping c^2 of the kinetic energy; the two integrators agree."""
    b, h = 0.25, 1.0
    frame = rocking_frame(b, h, 0.2)
    k = math.tan(math.atan2(b, h))
    mechs = [Mechanism(m.direction, m.hinges, k) for m in (FRAME_L, FRAME_R)]
    lim = LimitResult(frame, k, k, mechs[0], mechs[1], None, None, method="analytic")
    model = prepare(frame, "momentum", limit=lim)
    c = model.impact.l_to_r
    motion = gm.oppenheim_pulse(-1.5 * k, 0.2)
    fast = respond(model, motion, t_end=6.0)
    ref = respond(model, motion, t_end=6.0, integrator="reference")
    assert fast.status == ref.status == "rest" and fast.activated
    assert len(fast.impacts) >= 3
    assert fast.impacts[:3] == pytest.approx(ref.impacts[:3], abs=1e-5)
    assert fast.peak == pytest.approx(ref.peak, rel=1e-5)
    for e in fast.events:
        if e.kind == "impact" and e.after != "rest":
            assert e.energy_ratio == pytest.approx(c * c, rel=1e-12)
            assert e.rate_after == pytest.approx(-c * e.rate_before, rel=1e-12)


# ------------------------------------------------------------------------- drawing
def test_displaced_polygons_move_rigidly(opp, tmp_path, rocking_frame):
    pytest.importorskip("matplotlib")
    from archrock.reports.plots import displaced_hinges, displaced_outlines

    frame = rocking_frame(0.25, 1.0, 0.2)
    k = 0.25
    mechs = [Mechanism(m.direction, m.hinges, k) for m in (FRAME_L, FRAME_R)]
    model = prepare(frame, "momentum", limit=LimitResult(frame, k, k, *mechs, None, None))
    rest = displaced_outlines(model, "rest", 0.0)
    moved = displaced_outlines(model, "l", 0.1)
    fl = model.mech_l
    for i in range(frame.n):
        assert np.allclose(rest[i][:-1], frame.outline(i)) and np.array_equal(rest[i][0], rest[i][-1])
        d0 = np.linalg.norm(rest[i][:, None] - rest[i][None], axis=-1)
        d1 = np.linalg.norm(moved[i][:, None] - moved[i][None], axis=-1)
        assert np.allclose(d0, d1, atol=1e-12)
    # the columns turn by phi about their pivots (A, D stay), the beam translates with B
    th = -0.1  # M_l turns the columns clockwise
    rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
    a = fl.points[0]
    assert np.allclose(moved[0], (rest[0] - a) @ rot.T + a, atol=1e-12)
    hinges = displaced_hinges(model, "l", 0.1)
    assert np.allclose(hinges[[0, 3]], fl.points[[0, 3]])
    shift = hinges[1] - fl.points[1]
    assert np.allclose(moved[1], rest[1] + shift, atol=1e-12)


def test_polygon_animation(opp, tmp_path):
    pytest.importorskip("matplotlib")
    PIL = pytest.importorskip("PIL.Image")
    from archrock.reports.animate import animate_response

    arch, lim, _, _ = opp
    poly = as_polygon(arch, 12)
    res = respond(prepare(poly, "paper", limit=polygon_limit(poly, lim)),
                  gm.oppenheim_pulse(-1.0, 0.2), t_end=1.0)
    path = animate_response(res, tmp_path / "poly.gif", max_frames=3, dpi=30)
    with PIL.open(path) as im:
        assert im.n_frames == 3


# ------------------------------------------------------------------------- batch: circular only
def test_prepare_batch_refuses_polygon_data():
    from archrock.dynamics.batch import prepare_batch

    poly = as_polygon(geometry.oppenheim_arch(), 5)
    a = geometry.oppenheim_arch()
    with pytest.raises(ArchInputError, match="circular arches only"):
        prepare_batch(poly, a.radii, a.thicknesses)
    with pytest.raises(ArchInputError, match="circular arches only"):
        prepare_batch([poly, poly], [a.radii] * 2, [a.thicknesses] * 2)
    with pytest.raises(ArchInputError, match="circular arches only"):
        prepare_batch([np.array(p) for p in poly.intrados], a.radii, a.thicknesses)
    ok = prepare_batch(a.spans, a.radii, a.thicknesses, impact="momentum")
    assert ok.error[0] == ""
