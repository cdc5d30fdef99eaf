"""Geometry: exact annular-sector properties, joints, contact surfaces, random arches, input errors."""

import math
import re

import numpy as np
import pytest
from scipy.integrate import dblquad

from archrock.errors import ArchInputError
from archrock.geometry import (Arch, nominal_arch, oppenheim_arch, random_arch,
                               random_spans_thicknesses_radii)


def _sector_by_quadrature(r_in, r_out, th_lo, th_hi):
    """Area, centroid and polar moment about the centroid of an annular sector, by dblquad."""
    opts = dict(epsabs=1e-13, epsrel=1e-12)

    def integral(f):  # integrand f(r, theta), area element r dr dtheta
        return dblquad(lambda r, th: f(r, th) * r, th_lo, th_hi, r_in, r_out, **opts)[0]

    area = integral(lambda r, th: 1.0)
    xg = integral(lambda r, th: r * math.cos(th)) / area
    yg = integral(lambda r, th: r * math.sin(th)) / area
    polar = integral(lambda r, th: (r * math.cos(th) - xg) ** 2 + (r * math.sin(th) - yg) ** 2)
    return area, np.array([xg, yg]), polar


IRREGULAR = Arch(np.radians([30.0, 25.0, 40.0, 20.0, 42.5]), np.array([10.0, 10.2, 9.9, 10.1, 10.0]),
                 np.array([1.5, 1.2, 1.6, 1.0, 1.4]), density=2400.0)


@pytest.mark.parametrize("arch,i", [(oppenheim_arch(), 0), (oppenheim_arch(), 3),
                                    (IRREGULAR, 1), (IRREGULAR, 4)])
def test_sector_properties_match_numerical_integration(arch, i):
    psi = arch.joint_angles
    r_in = arch.radii[i] - arch.thicknesses[i] / 2
    r_out = arch.radii[i] + arch.thicknesses[i] / 2
    area, centroid, polar = _sector_by_quadrature(r_in, r_out, psi[i + 1], psi[i])
    assert arch.areas[i] == pytest.approx(area, rel=1e-10)
    assert arch.masses[i] == pytest.approx(arch.density * area, rel=1e-10)
    np.testing.assert_allclose(arch.centroids[i], centroid, rtol=0, atol=1e-9)
    assert arch.inertias[i] == pytest.approx(arch.density * polar, rel=1e-8)
    assert arch.weights[i] == pytest.approx(9.81 * arch.density * area, rel=1e-10)


def test_oppenheim_mass_properties_closed_form():
    a = oppenheim_arch()
    half = math.radians(157.5) / 14
    ri, ro = 9.25, 10.75
    assert a.areas == pytest.approx(np.full(7, half * (ro**2 - ri**2)))
    rg = 2 / 3 * (ro**3 - ri**3) / (ro**2 - ri**2) * math.sin(half) / half
    np.testing.assert_allclose(np.hypot(*a.centroids.T), rg, rtol=1e-13)
    # the crown voussoir of a symmetric arch sits on the y axis
    assert a.centroids[3, 0] == pytest.approx(0.0, abs=1e-12)
    assert a.centroids[3, 1] == pytest.approx(rg)


def test_joint_angles():
    for arch in (oppenheim_arch(), IRREGULAR, random_arch(seed=3)):
        psi = arch.joint_angles
        alpha = arch.embrace
        assert psi.shape == (arch.n + 1,)
        assert psi[0] == pytest.approx(math.pi / 2 + alpha / 2, abs=1e-14)
        assert psi[-1] == pytest.approx(math.pi / 2 - alpha / 2, abs=1e-14)
        np.testing.assert_allclose(-np.diff(psi), arch.spans, atol=1e-14)
    assert oppenheim_arch().joint_angles[0] == pytest.approx(math.radians(90 + 78.75))
    assert IRREGULAR.embrace == pytest.approx(math.radians(157.5))


def test_contact_surfaces_of_mismatched_neighbours():
    a = IRREGULAR
    ri = a.radii - a.thicknesses / 2
    ro = a.radii + a.thicknesses / 2
    # springings use their own voussoir's extent
    assert a.contact_inner[0] == ri[0] and a.contact_outer[0] == ro[0]
    assert a.contact_inner[-1] == ri[-1] and a.contact_outer[-1] == ro[-1]
    for j in range(1, a.n):
        assert a.contact_inner[j] == pytest.approx(max(ri[j - 1], ri[j]))
        assert a.contact_outer[j] == pytest.approx(min(ro[j - 1], ro[j]))
    # joint 1: voussoir 0 spans 9.25..10.75, voussoir 1 spans 9.6..10.8 -> overlap 9.6..10.75
    assert (a.contact_inner[1], a.contact_outer[1]) == pytest.approx((9.6, 10.75))
    # joint 4: voussoir 3 spans 9.6..10.6, voussoir 4 spans 9.3..10.7 -> overlap 9.6..10.6
    assert (a.contact_inner[4], a.contact_outer[4]) == pytest.approx((9.6, 10.6))
    p = a.joint_point(1, "extrados")
    assert np.hypot(*p) == pytest.approx(10.75)
    assert math.atan2(p[1], p[0]) == pytest.approx(a.joint_angles[1])


def test_random_arch_reproducible_and_spans_add_up():
    a1 = random_arch(seed=42)
    a2 = random_arch(seed=42)
    a3 = random_arch(seed=43)
    for f in ("spans", "radii", "thicknesses"):
        np.testing.assert_array_equal(getattr(a1, f), getattr(a2, f))
    assert not np.allclose(a1.thicknesses, a3.thicknesses)
    for seed in range(20):
        a = random_arch(seed=seed, spread_span=0.3)
        assert a.embrace == pytest.approx(math.radians(157.5), abs=1e-13)
        assert not np.allclose(a.spans, a.spans[0])
    # the same stream through a SeedSequence or a Generator
    ss = np.random.SeedSequence(7)
    b1 = random_arch(seed=np.random.SeedSequence(7))
    b2 = random_arch(rng=np.random.default_rng(ss))
    np.testing.assert_array_equal(b1.radii, b2.radii)


def test_zero_spreads_give_nominal_exactly():
    nom = nominal_arch(8.0, 120.0, 0.9, 9)
    a = random_arch(nom, seed=5, spread_span=0.0, spread_thickness=0.0, spread_radius=0.0)
    np.testing.assert_array_equal(a.spans, nom.spans)
    np.testing.assert_array_equal(a.radii, nom.radii)
    np.testing.assert_array_equal(a.thicknesses, nom.thicknesses)


def test_random_distribution_convention():
    nom = oppenheim_arch()
    R, t, s = 10.0, 1.5, math.radians(157.5) / 7
    sa, st, sr = 0.2, 0.1, 0.05
    # the mapping itself, at the extremes and the centre of U
    u = np.array([[1, -1, 0, 0, 0, 0, 0], [1, -1, 0, 0.5, 0, 0, 0], [1, -1, 0, 0, -0.5, 0, 0]], float)
    spans, thick, radii = random_spans_thicknesses_radii(nom, u, sa, st, sr)
    np.testing.assert_allclose(thick[:5], t * np.array([1 + st, 1 - st, 1, 1 + st / 2, 1]))
    np.testing.assert_allclose(radii[:5], R + sr * t * np.array([1, -1, 0, 0, -0.5]))
    raw = s * np.array([1 + sa, 1 - sa, 1, 1, 1, 1, 1])
    np.testing.assert_allclose(spans, raw * (7 * s / raw.sum()))
    # many draws: inside the bounds, filling them, with independent uniform spreads
    arches = [random_arch(nom, seed=k, spread_span=sa, spread_thickness=st, spread_radius=sr)
              for k in range(2000)]
    T = np.array([a.thicknesses for a in arches])
    Rs = np.array([a.radii for a in arches])
    S = np.array([a.spans for a in arches])
    assert T.min() >= t * (1 - st) and T.max() <= t * (1 + st)
    assert T.min() < t * (1 - 0.98 * st) and T.max() > t * (1 + 0.98 * st)
    assert Rs.min() >= R - sr * t and Rs.max() <= R + sr * t
    assert Rs.min() < R - 0.98 * sr * t and Rs.max() > R + 0.98 * sr * t
    ratio = S.max(axis=1) / S.min(axis=1)
    assert ratio.max() <= (1 + sa) / (1 - sa) + 1e-12
    # uniform on [-1, 1]: mean 0, variance 1/3
    ut = (T / t - 1) / st
    assert abs(ut.mean()) < 0.02 and ut.var() == pytest.approx(1 / 3, rel=0.05)
    ur = (Rs - R) / (sr * t)
    assert abs(ur.mean()) < 0.02 and ur.var() == pytest.approx(1 / 3, rel=0.05)
    assert abs(np.corrcoef(ut.ravel(), ur.ravel())[0, 1]) < 0.04


def test_mirrored_twice_is_identity():
    a = random_arch(seed=11)
    m = a.mirrored()
    np.testing.assert_array_equal(m.spans, a.spans[::-1])
    np.testing.assert_allclose(m.centroids[::-1] * [-1, 1], a.centroids, atol=1e-12)
    mm = m.mirrored()
    for f in ("spans", "radii", "thicknesses"):
        np.testing.assert_array_equal(getattr(mm, f), getattr(a, f))
    assert mm.density == a.density
    assert oppenheim_arch().is_symmetric() and not a.is_symmetric()


def test_dict_round_trip():
    a = random_arch(seed=9)
    d = a.to_dict()
    assert len(d["voussoirs"]) == 7 and set(d["voussoirs"][0]) == {"span_deg", "radius", "thickness"}
    b = Arch.from_dict(d)
    np.testing.assert_allclose(b.spans, a.spans, rtol=1e-15)
    np.testing.assert_array_equal(b.radii, a.radii)
    np.testing.assert_array_equal(b.thicknesses, a.thicknesses)
    assert b.density == a.density
    np.testing.assert_allclose(b.inertias, a.inertias, rtol=1e-13)


def _arch(spans_deg=(50, 50, 50), radii=(10, 10, 10), thick=(1, 1, 1)):
    return Arch(np.radians(spans_deg), np.array(radii, float), np.array(thick, float))


@pytest.mark.parametrize("kwargs,field", [
    (dict(thick=(1, 0, 1)), "thickness"),
    (dict(thick=(1, -0.5, 1)), "thickness"),
    (dict(thick=(1, 1, 20)), "thickness"),
    (dict(thick=(1, 1, 25)), "thickness"),
    (dict(spans_deg=(50, 0, 50)), "span"),
    (dict(spans_deg=(50, -5, 50)), "span"),
    (dict(spans_deg=(120, 120, 120)), "spans"),
    (dict(spans_deg=(150, 150, 100)), "spans"),
    (dict(spans_deg=(90, 90), radii=(10, 10), thick=(1, 1)), "voussoirs"),
    (dict(spans_deg=(50, 50, 50), radii=(10, 10), thick=(1, 1, 1)), "voussoirs"),
    (dict(radii=(10, 12, 10)), "joint 1"),
    (dict(radii=(10, 10, 0)), "radius"),
    (dict(spans_deg=(50, float("nan"), 50)), "spans"),
    (dict(radii=(10, float("inf"), 10)), "radii"),
    (dict(thick=(1, 1, float("nan"))), "thicknesses"),
])
def test_bad_arch_raises_naming_the_field(kwargs, field):
    with pytest.raises(ArchInputError, match=field):
        _arch(**kwargs)


@pytest.mark.parametrize("kwargs,field", [
    (dict(thickness=0.0), "thickness"),
    (dict(thickness=20.0), "thickness"),
    (dict(thickness=float("nan")), "thickness"),
    (dict(radius=-1.0), "radius"),
    (dict(radius=float("inf")), "radius"),
    (dict(embrace_deg=360.0), "embrace"),
    (dict(embrace_deg=0.0), "embrace"),
    (dict(voussoirs=2), "voussoirs"),
    (dict(voussoirs=4.5), "voussoirs"),
    (dict(density=0.0), "density"),
])
def test_bad_nominal_raises_naming_the_field(kwargs, field):
    with pytest.raises(ArchInputError, match=field):
        nominal_arch(**kwargs)


def test_bad_random_spreads():
    with pytest.raises(ArchInputError, match="spread_span"):
        random_arch(seed=1, spread_span=-0.1)
    with pytest.raises(ArchInputError, match="spread_thickness"):
        random_arch(seed=1, spread_thickness=1.0)
    with pytest.raises(ArchInputError, match="spread_radius"):
        random_arch(seed=1, spread_radius=float("nan"))


GOOD = {"span_deg": 30.0, "radius": 10.0, "thickness": 1.0}


@pytest.mark.parametrize("data,field", [
    ([GOOD] * 3, "geometry"),
    ("not a dict", "geometry"),
    ({}, "voussoirs"),
    ({"voussoirs": []}, "voussoirs"),
    ({"voussoirs": GOOD}, "voussoirs"),
    ({"voussoirs": [GOOD, GOOD, 5]}, r"voussoirs\[2\]"),
    ({"voussoirs": [GOOD, {"radius": 10.0, "thickness": 1.0}, GOOD]}, r"voussoirs\[1\]\.span_deg"),
    ({"voussoirs": [GOOD, GOOD, {**GOOD, "thickness": "1"}]}, r"voussoirs\[2\]\.thickness"),
    ({"voussoirs": [GOOD, GOOD, {**GOOD, "radius": True}]}, r"voussoirs\[2\]\.radius"),
    ({"voussoirs": [GOOD, GOOD, {**GOOD, "radius": None}]}, r"voussoirs\[2\]\.radius"),
    ({"voussoirs": [{**GOOD, "span_deg": float("nan")}, GOOD, GOOD]}, r"voussoirs\[0\]\.span_deg"),
    ({"voussoirs": [GOOD, {**GOOD, "thickness": float("inf")}, GOOD]}, r"voussoirs\[1\]\.thickness"),
    ({"voussoirs": [GOOD, GOOD]}, "voussoirs"),
    ({"voussoirs": [GOOD, {**GOOD, "thickness": -1.0}, GOOD]}, "thickness"),
    ({"voussoirs": [GOOD] * 3, "density": "heavy"}, "density"),
    ({"voussoirs": [GOOD] * 3, "density": -2.0}, "density"),
])
def test_malformed_dict_raises_naming_the_field(data, field):
    with pytest.raises(ArchInputError, match=field):
        Arch.from_dict(data)


# ---- issue 17: polygon files whose order, sides or loads cannot be meant ----------------------
def _polygon_dict():
    from archrock.geometry import as_polygon

    return as_polygon(oppenheim_arch(), 6).to_dict()


def _from(d):
    from archrock.geometry import PolygonArch

    return PolygonArch.from_dict(d)


def test_voussoirs_listed_right_to_left_are_named():
    """Both ways of listing from the right (the list reversed; the list and each line reversed)
    ended in "cannot stand ... increase the thickness"."""
    d = _polygon_dict()
    assert _from(d).n == 7
    back = {**d, "voussoirs": d["voussoirs"][::-1]}
    with pytest.raises(ArchInputError, match=r"^voussoirs: listed from right to left \(voussoir 0 "
                       r"at x = 8\.315 m, voussoir 6 at x = -8\.315 m\); allowed the list from "
                       r"the left springing, each intrados and extrados from left to right$"):
        _from(back)
    mirrored = {**d, "voussoirs": [{"intrados": v["intrados"][::-1], "extrados": v["extrados"][::-1]}
                                   for v in d["voussoirs"][::-1]]}
    with pytest.raises(ArchInputError, match=r"^voussoirs: listed from right to left \(voussoir 0 "
                       r"at x = 9\.808 m, voussoir 6 at x = -9\.808 m\)"):
        _from(mirrored)


@pytest.mark.parametrize("which", [[3], list(range(7))])
def test_swapped_intrados_and_extrados_are_named(which):
    d = _polygon_dict()
    vs = [dict(v) for v in d["voussoirs"]]
    for i in which:
        vs[i] = {"intrados": vs[i]["extrados"], "extrados": vs[i]["intrados"]}
    with pytest.raises(ArchInputError, match=rf"^voussoirs\[{which[0]}\]: intrados and extrados "
                       r"swapped \(its 'intrados' lies on the outer side of the ring\)"):
        _from({**d, "voussoirs": vs})


@pytest.mark.parametrize("at, where, gap", [((140.0, 9.0), "beside", 129.5),
                                            ((30.0, 9.0), "beside", 19.46),
                                            ((0.0, -30.0), "below", 31.8),
                                            ((0.0, 200.0), "above", 189.3)])
def test_loads_far_from_the_arch_are_refused(at, where, gap):
    d = _polygon_dict()
    d["loads"] = [{"voussoir": 3, "mass": 8000.0, "at": list(at)}]
    with pytest.raises(ArchInputError, match=rf"^loads\[0\]\.at: \({at[0]:g}, {at[1]:g}\) m is "
                       rf"{gap:g} m {where} the arch \(x -10\.54\.\.10\.54 m, y 1\.805\.\.10\.74 m, "
                       rf"extent 21\.09 m\); allowed within"):
        _from(d)
    # near the arch, or above it like a pier or a deep fill: accepted
    for ok in ((0.0, 11.0), (12.0, 9.0), (0.0, 60.0)):
        d["loads"] = [{"voussoir": 3, "mass": 8000.0, "at": list(ok)}]
        assert _from(d).loads[0].at == pytest.approx(ok)
    # the circular Arch checks its loads the same way (its frame: the centre at the origin)
    from archrock.geometry import Load

    a = oppenheim_arch()
    with pytest.raises(ArchInputError, match=r"^loads\[0\]\.at: \(140, 9\) m is .* beside the arch"):
        Arch(a.spans, a.radii, a.thicknesses, a.density, "far", (Load(3, 8000.0, (140.0, 9.0)),))


# ---- issue 17: bounded voussoir counts and lengths ---------------------------------------------
def test_voussoir_count_is_bounded_by_name():
    """--voussoirs 1e6 ran for 40 s and ended in Python advice; now refused at once."""
    from archrock.geometry import family_arch

    assert nominal_arch(voussoirs=2000).n == 2000
    for make in (lambda n: nominal_arch(voussoirs=n),
                 lambda n: family_arch("pointed", 10.0, 7.0, 1.0, n)):
        with pytest.raises(ArchInputError, match=r"^voussoirs: 1000000; allowed 3 to 2000 \("):
            make(1_000_000)
        with pytest.raises(ArchInputError, match=r"^voussoirs: 2001; allowed 3 to 2000"):
            make(2001)
    a = oppenheim_arch()
    with pytest.raises(ArchInputError, match=r"^voussoirs: 2001; allowed 3 to 2000"):
        Arch(np.full(2001, 1e-3), np.full(2001, 10.0), np.full(2001, 1.0))


@pytest.mark.parametrize("kwargs, field, value", [
    (dict(radius=1e12), "radius", "1e+12"), (dict(radius=1e300, thickness=1e299), "radius", "1e+300"),
    (dict(radius=1e-300, thickness=1e-301), "radius", "1e-300"),
    (dict(thickness=1e-9), "thickness", "1e-09"), (dict(radius=2e9, thickness=1.0), "radius", "2e+09")])
def test_lengths_outside_a_masonry_arch_are_refused_without_numpy_warnings(kwargs, field, value):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow warning may leak before the refusal
        with pytest.raises(ArchInputError, match=rf"^{field}: {re.escape(value)} m is out of range; allowed "
                           r"1e-08 m to 1e\+08 m \(units\? lengths are in metres\)$"):
            nominal_arch(**kwargs)


def test_family_lengths_are_bounded_and_the_bounds_themselves_build():
    from archrock.geometry import family_arch
    from archrock.statics.limit import limit_analysis

    with pytest.raises(ArchInputError, match=r"^span: 1e\+09 m is out of range; allowed 1e-08 m"):
        family_arch("circular", 1e9, 1e8, 1e7, 7)
    with pytest.raises(ArchInputError, match=r"^thickness_crown: 1e-09 m is out of range"):
        family_arch("pointed", 10.0, 7.0, 1.0, 7, thickness_crown=1e-9)
    # the extremes of the range are ordinary arches: the same k (scale invariance)
    k = limit_analysis(nominal_arch(10.0, 157.5, 1.5, 7)).k
    assert limit_analysis(nominal_arch(1e4, 157.5, 1.5e3, 7)).k == pytest.approx(k, rel=1e-9)
    assert limit_analysis(nominal_arch(1e-2, 157.5, 1.5e-3, 7)).k == pytest.approx(k, rel=1e-9)
    # a constructed arch (scaled, from a file) has the wider range 1e-9..1e9 m
    assert oppenheim_arch().scaled(1e3).radii[0] == pytest.approx(1e4)
    with pytest.raises(ArchInputError, match=r"^radii: 1e\+10 m is out of range; allowed 1e-09 m "
                                             r"to 1e\+09 m"):
        oppenheim_arch().scaled(1e9)
