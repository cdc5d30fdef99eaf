"""The arch families of geometry.families: shapes, thickness, joints, fill, refusals."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from archrock.errors import ArchInputError
from archrock.geometry import (Arch, FamilyArch, PolygonArch, family_arch, oppenheim_arch,
                               random_arch)
from archrock.statics.limit import limit_analysis
from archrock.geometry.centreline import SHAPES, centreline, three_centred_radii

S = 10.0
RISE = {"circular": 3.0, "pointed": 7.0, "elliptical": 3.5, "three-centred": 3.5,
        "parabolic": 5.0, "catenary": 5.0}


def _centreline_length(shape, span, rise):
    """Independent arc lengths (closed forms or quad of the centreline's own equation)."""
    a, f = span / 2, rise
    if shape == "circular":
        r = (a * a + f * f) / (2 * f)
        return 2 * r * math.asin(a / r) if f <= a else 2 * r * (math.pi - math.asin(a / r))
    if shape == "parabolic":
        return quad(lambda x: math.hypot(1, 2 * f * x / a**2), -a, a)[0]
    if shape == "elliptical":
        return quad(lambda th: math.hypot(a * math.sin(th), f * math.cos(th)), 0, math.pi)[0]
    if shape == "pointed":
        c = (a * a - f * f) / span
        rho = a - c
        return 2 * rho * math.atan2(f, -c)
    if shape == "three-centred":
        r1, r2 = three_centred_radii(span, rise)
        g = math.atan2(r2 - f, -(a - r1))  # the tangent point's direction from the crown centre
        return 2 * r1 * (math.pi - g) + r2 * (2 * g - math.pi)
    from scipy.optimize import brentq

    big_a = brentq(lambda k: k * (math.cosh(a / k) - 1) - f, 0.1, 1e3)
    return 2 * big_a * math.sinh(a / big_a)


@pytest.mark.parametrize("shape", SHAPES)
def test_centreline_springings_crown_and_length(shape):
    line = centreline(shape, S, RISE[shape])
    p, _ = line.eval(np.array([0.0, line.length / 2, line.length]))
    np.testing.assert_allclose(p, [[-S / 2, 0], [0, RISE[shape]], [S / 2, 0]], atol=1e-9)
    assert line.length == pytest.approx(_centreline_length(shape, S, RISE[shape]), rel=1e-9)


@pytest.mark.parametrize("shape", SHAPES)
def test_constant_thickness_area_is_t_times_length_and_faces_are_t(shape):
    t = 0.8
    arch = family_arch(shape, S, RISE[shape], t, 8, exact=False)
    assert isinstance(arch, FamilyArch) and arch.n == 8
    # a band of constant width t about a curve has area t L (curvature terms cancel); a pointed
    # arch: two annuli about (-+c, 0), each cut by x = 0
    expected = t * _centreline_length(shape, S, RISE[shape])
    if shape == "pointed":
        c = (S * S / 4 - RISE[shape] ** 2) / S
        rho = S / 2 - c
        expected = 2 * quad(lambda r: r * (math.pi - math.acos(c / r)), rho - t / 2, rho + t / 2)[0]
    assert arch.areas.sum() == pytest.approx(expected, rel=1e-5)
    lengths = np.hypot(*(arch.joint_points[:, 1] - arch.joint_points[:, 0]).T)
    if shape == "pointed":  # the crown joint is vertical, between the offset arcs' meeting points
        lengths = np.delete(lengths, 4)
    np.testing.assert_allclose(lengths, t, rtol=1e-9)
    mid = arch.joint_points.mean(axis=1)
    np.testing.assert_allclose(mid[[0, -1]], [[-S / 2, 0], [S / 2, 0]], atol=1e-9)
    assert mid[4] == pytest.approx([0.0, RISE[shape]] if shape != "pointed" else mid[4])
    assert arch.is_symmetric(1e-7)
    assert arch.size == pytest.approx(S / 2)


def test_semicircle_area_error_below_1e_5():
    arch = family_arch("circular", 10.0, 5.0, 1.0, 7, exact=False)
    exact = math.pi / 2 * (5.5**2 - 4.5**2)
    assert abs(arch.areas.sum() / exact - 1) < 1e-5
    coarse = family_arch("circular", 10.0, 5.0, 1.0, 7, exact=False, points_per_rad=20)
    assert abs(coarse.areas.sum() / exact - 1) > 1e-4


def test_circular_exact_arch_matches_the_polygon_one_shifted():
    s, f = 12.0, 3.0
    exact = family_arch("circular", s, f, 0.6, 9, loads=[{"voussoir": 4, "mass": 100.0,
                                                          "at": [0.0, 3.5]}])
    poly = family_arch("circular", s, f, 0.6, 9, exact=False,
                       loads=[{"voussoir": 4, "mass": 100.0, "at": [0.0, 3.5]}])
    assert isinstance(exact, Arch) and isinstance(poly, FamilyArch)
    r = (36 + 9) / 6.0
    assert exact.radii[0] == pytest.approx(r)
    shift = np.array([0.0, f - r])
    np.testing.assert_allclose(exact.joint_points + shift, poly.joint_points, atol=1e-12)
    np.testing.assert_allclose(exact.centroids + shift, poly.centroids, atol=1e-4)
    np.testing.assert_allclose(exact.masses, poly.masses, rtol=1e-4)
    # the semicircle and a horseshoe arch
    assert math.degrees(family_arch("circular", 10, 5, 1, 7).embrace) == pytest.approx(180)
    assert math.degrees(family_arch("circular", 10, 10, 1, 7).embrace) == pytest.approx(
        180 + 2 * math.degrees(math.atan(0.75)))


def test_pointed_crown_joint_or_keystone():
    even = family_arch("pointed", 10.0, 8.0, 0.8, 6)
    crown = even.joint_points[3]
    assert crown[0, 0] == pytest.approx(0, abs=1e-12) and crown[1, 0] == pytest.approx(0, abs=1e-12)
    assert crown[0, 1] < 8.0 < crown[1, 1]
    odd = family_arch("pointed", 10.0, 8.0, 0.8, 7)
    key = odd.intrados[3]
    assert np.any(np.abs(key[:, 0]) < 1e-12)  # the pointed vertex of the keystone's intrados
    assert np.argmax(odd.extrados[3][:, 1]) == np.argmin(np.abs(odd.extrados[3][:, 0]))
    assert odd.is_symmetric(1e-7)


def test_three_centred_construction():
    r1, r2 = three_centred_radii(10.0, 5.0)
    assert r1 == pytest.approx(5.0) and r2 == pytest.approx(5.0)  # the semicircle
    a, f = 5.0, 3.0
    r1, r2 = three_centred_radii(2 * a, f)
    assert 0 < r1 < f < r2
    # side centre (-(a - r1), 0) and crown centre (0, f - r2) at distance r2 - r1: tangent arcs
    assert math.hypot(a - r1, f - r2) == pytest.approx(r2 - r1)


def test_vertical_joints_are_vertical_through_the_division_points():
    arch = family_arch("elliptical", 10.0, 3.0, 0.6, 7, joints="vertical")
    normal = family_arch("elliptical", 10.0, 3.0, 0.6, 7)
    jp = arch.joint_points
    np.testing.assert_allclose(jp[1:-1, 0, 0], jp[1:-1, 1, 0], atol=1e-12)
    # the centreline's division points: the mid-points of the normal joints
    np.testing.assert_allclose(jp[1:-1, 0, 0], normal.joint_points[1:-1].mean(axis=1)[:, 0],
                               atol=1e-9)
    np.testing.assert_allclose(jp[[0, -1]], normal.joint_points[[0, -1]], atol=1e-12)
    assert arch.areas.sum() == pytest.approx(normal.areas.sum(), rel=1e-5)


def test_thickness_varies_linearly_to_the_crown():
    arch = family_arch("parabolic", 10.0, 4.0, 1.0, 6, thickness_crown=0.5)
    lengths = np.hypot(*(arch.joint_points[:, 1] - arch.joint_points[:, 0]).T)
    np.testing.assert_allclose(lengths, [1.0, 5 / 6, 4 / 6, 0.5, 4 / 6, 5 / 6, 1.0], rtol=1e-9)


def test_with_thickness_factor_and_scaled_rebuild_the_family():
    arch = family_arch("catenary", 10.0, 5.0, 0.8, 7, thickness_crown=0.6, name="cat")
    thin = arch.with_thickness_factor(0.5)
    assert isinstance(thin, FamilyArch) and thin.name == "cat"
    lengths = np.hypot(*(thin.joint_points[:, 1] - thin.joint_points[:, 0]).T)
    assert lengths[0] == pytest.approx(0.4)
    np.testing.assert_allclose(thin.joint_points.mean(axis=1), arch.joint_points.mean(axis=1),
                               atol=1e-9)
    big = arch.scaled(3.0)
    assert isinstance(big, FamilyArch)
    np.testing.assert_allclose(big.masses, 9 * arch.masses, rtol=1e-9)
    exact = family_arch("circular", 10.0, 4.0, 1.0, 7)
    assert exact.with_thickness_factor(0.5).thicknesses[0] == 0.5


def test_fill_over_a_semicircle():
    re, level, rho = 5.5, 7.0, 1800.0
    arch = family_arch("circular", 10.0, 5.0, 1.0, 6, fill={"level": level, "density": rho})
    assert isinstance(arch, FamilyArch)  # a fill needs the polygon form
    total = sum(ld.mass for ld in arch.loads)
    exact = rho * (2 * re * level - math.pi * re**2 / 2)
    assert total == pytest.approx(exact, rel=1e-4)
    assert len(arch.loads) == 6 and len(arch.fill_regions) == 6
    assert arch.is_symmetric(1e-7)
    # the voussoir left of the crown: its extrados from 120 to 90 deg, x from -Re/2 to 0
    crown = quad(lambda x: level - math.sqrt(re**2 - x**2), -re / 2, 0)[0]
    assert arch.loads[2].mass == pytest.approx(rho * crown, rel=1e-4)
    # a level below the crown's extrados: those voussoirs get none
    low = family_arch("circular", 10.0, 5.0, 1.0, 6, fill={"level": 3.0, "density": rho})
    assert {ld.voussoir for ld in low.loads} == {0, 1, 4, 5}  # extrados above y = 3 at 2, 3
    # the fill is recomputed for a thinner arch
    thin = arch.with_thickness_factor(0.5)
    assert sum(ld.mass for ld in thin.loads) > total


@pytest.mark.parametrize("kwargs, field", [
    (dict(shape="oval"), "shape"),
    (dict(span=0.0), "span"),
    (dict(span=-1.0), "span"),
    (dict(thickness=0.0), "thickness"),
    (dict(voussoirs=2), "voussoirs"),
    (dict(voussoirs=3.5), "voussoirs"),
    (dict(joints="radial"), "joints"),
    (dict(shape="circular", rise=10.5), "rise"),
    (dict(shape="pointed", rise=5.0), "rise"),
    (dict(shape="three-centred", rise=6.0), "rise"),
    (dict(shape="elliptical", rise=0.0), "rise"),
    (dict(shape="parabolic", rise=float("nan")), "rise"),
    (dict(shape="parabolic", rise=20.0, thickness=1.5), "thickness"),  # crown radius 0.625 m
    (dict(shape="circular", rise=1.0, thickness=30.0), "thickness"),
    (dict(shape="elliptical", rise=1.0, thickness_crown=-1.0), "thickness_crown"),
    (dict(shape="circular", rise=8.0, joints="vertical"), "joints"),
    (dict(fill={"level": 6.0}), "fill"),
    (dict(fill={"level": 6.0, "density": 0.0}), "fill density"),
    (dict(shape="circular", rise=8.0, fill={"level": 9.0, "density": 1.0}), "fill"),
])
def test_refusals_name_the_field(kwargs, field):
    args = dict(shape="elliptical", span=10.0, rise=4.0, thickness=0.5, voussoirs=7)
    args.update(kwargs)
    shape, span, rise, t, n = (args.pop(k) for k in ("shape", "span", "rise", "thickness", "voussoirs"))
    with pytest.raises(ArchInputError, match=f"^{field}"):
        family_arch(shape, span, rise, t, n, exact=False, **args)


def test_random_arch_of_a_family_and_of_a_surveyed_polygon():
    nominal = family_arch("parabolic", 10, 5, 1, 7)
    a, b = random_arch(nominal, seed=1), random_arch(nominal, seed=1)
    assert np.array_equal(a.joint_points, b.joint_points)
    assert not np.allclose(a.joint_points, nominal.joint_points)
    with pytest.raises(ArchInputError, match="cannot be perturbed"):
        random_arch(PolygonArch(nominal.intrados, nominal.extrados), seed=1)
    with pytest.raises(ArchInputError, match="^spread_tilt_deg"):
        random_arch(oppenheim_arch(), seed=1, spread_tilt_deg=2.0)


def test_family_arch_is_a_polygon_arch_that_round_trips():
    arch = family_arch("three-centred", 10.0, 3.0, 0.7, 7, fill={"level": 4.5, "density": 1500})
    back = PolygonArch.from_dict(arch.to_dict())
    np.testing.assert_array_equal(back.joint_points, arch.joint_points)
    np.testing.assert_allclose(back.masses, arch.masses, rtol=1e-14)


def test_every_family_is_drawn_with_its_fill_and_loads(tmp_path):
    pytest.importorskip("matplotlib")
    from archrock.reports.plots import draw_arch, new_figure, save_figure, voussoir_bounds

    fig, axes = new_figure(1, len(SHAPES), figsize=(3.0 * len(SHAPES), 3))
    for ax, shape in zip(axes[0], SHAPES):
        arch = family_arch(shape, S, RISE[shape], 0.6, 7, exact=False,
                           fill={"level": RISE[shape] + 1.0, "density": 1800.0})
        patches = draw_arch(ax, arch, label_joints=True)
        assert len(patches) == 7
        assert voussoir_bounds(arch)[:, 1].max() == pytest.approx(RISE[shape] + 1.0)
    assert save_figure(fig, tmp_path / "families.png").stat().st_size > 10_000


def test_vertical_stereotomy_minimum_thickness_is_makris_and_alexakis():
    """Minimum thickness of a semicircular arch under its own weight with vertical joints
    approaches t/R = 0.1095 (Makris and Alexakis 2013), above Milankovitch's 0.1075 with radial
    joints; near the springings the springing voussoirs span the verticals that would miss the
    intrados, and the voussoirs between are shortened so that n is kept."""
    from archrock.statics.limit import minimum_thickness

    t = 0.11  # of a centreline radius 1
    vertical = family_arch("circular", 2.0, 1.0, t, 32, joints="vertical", exact=False)
    radial = family_arch("circular", 2.0, 1.0, t, 32, exact=False)
    assert vertical.n == 32 and radial.n == 32  # n honoured (3 springing joints would miss)
    tv = minimum_thickness(vertical).factor * t
    tr = minimum_thickness(radial).factor * t
    assert tv == pytest.approx(0.1095, abs=2e-4)
    assert tr == pytest.approx(0.1074, abs=3e-4) and tv > tr
    # at n = 8 every vertical joint crosses the ring: no joint is left out
    assert family_arch("circular", 2.0, 1.0, t, 8, joints="vertical", exact=False).n == 8


def test_pointed_arch_of_any_voussoir_count_builds_or_says_why():
    """A joint at the pointed crown sits on it exactly (n = 30 and 60 put it one ulp beside it
    and failed deep in the sampling); a crown voussoir too short for the thickness is refused
    by name, never an IndexError."""
    for n in (30, 40, 60):
        arch = family_arch("pointed", 10.0, 7.0, 1.0, n)
        crown = arch.joint_points[n // 2]
        assert arch.n == n and np.all(np.abs(crown[:, 0]) < 1e-12)  # the crown joint on the axis
        lim = limit_analysis(arch)
        assert lim.k_l == pytest.approx(lim.k_r, rel=1e-9)  # symmetric arch
    with pytest.raises(ArchInputError, match="^n: the joints beside the pointed crown"):
        family_arch("pointed", 10.0, 7.0, 1.0, 51)
    assert family_arch("pointed", 10.0, 7.0, 0.3, 51).n == 51


@pytest.mark.parametrize("n", [7, 12])
def test_vertical_joints_keep_the_voussoirs_asked_for(n):
    """Issue 17: --joints vertical --voussoirs 7 on a semicircle analysed 5 voussoirs (12 gave
    10) without a word.  The springing voussoirs now reach to the first equal division whose
    vertical crosses the ring and the rest of the centreline is divided equally: n voussoirs,
    every interior joint vertical and inside the ring, symmetric about the crown."""
    arch = family_arch("circular", 10.0, 5.0, 1.0, n, joints="vertical")
    assert arch.n == n
    for i in range(n - 1):
        a, b = arch.intrados[i][-1], arch.extrados[i][-1]
        assert a[0] == pytest.approx(b[0], abs=1e-12)  # vertical joint
        assert b[1] > a[1] + 0.5  # from the intrados up to the extrados, above it
        assert -4.5 < a[0] < 4.5  # crosses the intrados (radius 4.5), not the springing face
    # symmetric: voussoir i mirrors voussoir n-1-i
    x_joints = [arch.intrados[i][-1][0] for i in range(n - 1)]
    assert np.allclose(x_joints, [-x for x in reversed(x_joints)], atol=1e-12)


def test_vertical_joints_cli_reports_n_voussoirs():
    import json
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-m", "archrock", "limit", "--shape", "circular",
                          "--span", "10", "--rise", "5", "--thickness", "1", "--voussoirs", "7",
                          "--joints", "vertical", "--json"], capture_output=True, text=True,
                         check=True)
    assert len(json.loads(out.stdout)["voussoirs"]) == 7
