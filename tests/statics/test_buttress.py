"""The buttress question (archrock.statics.buttress): the least pier width under an arch, checked
against the overturning balance of a monolithic rectangular pier in closed form (Heyman, The
Stone Skeleton, 1995; Ochsendorf 2002), with the arch's thrust taken from the limit analysis of
the arch alone where it is unique (an arch at its minimum thickness); k against pier height;
friction on arches on piers (the rocking frame's sliding by hand)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from archrock.cli import main
from archrock.errors import ArchInputError, CannotStandError
from archrock.geometry import arch_from_dict, family_arch, nominal_arch, with_piers
from archrock.geometry.defect import _as_polygon
from archrock.statics.buttress import k_against_pier_height, minimum_pier_width
from archrock.statics.friction import friction_analysis, friction_needed
from archrock.statics.limit import limit_analysis, minimum_thickness
from archrock.statics.lp import _stands
from archrock.statics.thrust import thrust_range
from archrock.units import G

ARCH = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
RHO = 2000.0


def closed_form_width(H, V, s, h, rho=RHO):
    """The width W of a monolithic rectangular pier of height h [m] whose outer foot corner is
    on the thrust: moments about that corner of the arch's thrust H [N/m] (outward, at the pier
    top, h above the foot), its vertical reaction V [N/m] crossing the pier top s [m] outward
    of the inner face, and the pier's weight rho g h W at W / 2:
    H h = V (W - s) + rho g h W^2 / 2."""
    a = rho * G * h
    return (-V + math.sqrt(V * V + 2 * a * (H * h + V * s))) / a


@pytest.mark.parametrize("arch,h", [(ARCH, 4.0), (ARCH, 10.0),
                                    (family_arch("pointed", 10.0, 7.0, 0.9, 10), 6.0)])
def test_minimum_width_thrust_through_the_outer_foot_corner(arch, h):
    """At the minimum width the self-weight thrust passes through the pier's outer foot corner
    and the overturning balance, with the H, V and crossing of that thrust at the pier top,
    gives the width in closed form (to 1e-6; measured ~1e-11)."""
    r = minimum_pier_width(arch, h, tol=1e-10)
    assert r.governed_by == "pier"
    ap = r.structure
    # the thrust crosses the left foundation at its outer (extrados) end: the foot corner
    foot = ap.joint_points[0][1]
    assert foot[0] == pytest.approx(ap.joint_points[1][0][0] - r.width, abs=1e-12)
    fr = r.thrust.fractions
    assert fr[0] == pytest.approx(1.0, abs=1e-7) or fr[-1] == pytest.approx(1.0, abs=1e-7)
    H, V = r.springing_force
    s = ap.joint_points[1][0][0] - r.springing_point[0]    # outward of the inner face
    assert H > 0 and V > 0 and 0 <= s <= r.width
    assert closed_form_width(H, V, s, h) == pytest.approx(r.width, rel=1e-6)
    # bracketing: a hair narrower does not stand, the width found does
    poly = _as_polygon(arch)
    assert _stands(with_piers(poly, h, r.width))
    assert not _stands(with_piers(poly, h, r.width * (1 - 1e-6)))


def test_minimum_width_against_the_unique_thrust_of_a_minimum_thickness_arch():
    """An arch at its minimum thickness has one line of thrust (H_min = H_max on rigid
    supports, crossing each springing at its extrados end): the pier width from the closed form
    with that H, V = half the arch's weight and s = the springing joint's width, against the
    bisection with the static program on the arch on piers (to 1e-6)."""
    fam = family_arch("circular", 10.0, 5.0, 0.8, 9)
    mt = minimum_thickness(fam, tol=1e-12)
    thin = fam.with_thickness_factor(mt.factor)
    tr = thrust_range(thin)
    assert tr.thrust_max == pytest.approx(tr.thrust_min, rel=1e-9)       # unique
    assert any(h.joint == 0 and h.edge == "extrados" for h in tr.hinges_min)
    H = tr.thrust_min
    V = 0.5 * float(np.sum(thin.masses)) * G
    jp = thin.joint_points[0]
    s = jp[0][0] - jp[1][0]
    for h in (3.0, 8.0):
        r = minimum_pier_width(thin, h, tol=1e-10)
        assert r.width == pytest.approx(closed_form_width(H, V, s, h), rel=1e-6)
        assert r.springing_force[0] == pytest.approx(H, rel=1e-6)


def test_minimum_width_grows_with_height():
    ws = [minimum_pier_width(ARCH, h, tol=1e-7 if h == 4.0 else 1e-5).width
          for h in (2.0, 4.0, 8.0)]
    assert ws[0] < ws[1] < ws[2]
    assert ws[1] == pytest.approx(1.197882, abs=1e-6)


def test_minimum_width_with_batter_and_courses():
    w = 1.197882
    battered = minimum_pier_width(ARCH, 4.0, batter=0.1)
    assert battered.width < w
    assert battered.structure.block_kinds[0] == "buttress"
    # courses: the foot governs, the bed joints keep the thrust inside (same width)
    assert minimum_pier_width(ARCH, 4.0, courses=4).width == pytest.approx(w, abs=2e-6)


def test_low_piers_governed_by_the_springing():
    """Piers 5 cm high: the narrowest pier allowed (the springing joint's 0.8 m) stands."""
    r = minimum_pier_width(ARCH, 0.05)
    assert r.governed_by == "springing" and r.width == pytest.approx(0.8, rel=1e-9)
    assert r.iterations == 0


def test_no_width_up_to_the_bound():
    with pytest.raises(CannotStandError, match="no width up to max_width = 1 m"):
        minimum_pier_width(ARCH, 4.0, max_width=1.0)
    thin = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.2, voussoirs=9)
    with pytest.raises(CannotStandError, match="even on rigid supports"):
        minimum_pier_width(thin, 4.0)


@pytest.mark.parametrize("kwargs,start", [
    ({"height": 0.0}, "height:"), ({"height": -1.0}, "height:"), ({"height": 4.0, "tol": 0.0}, "tol:"),
    ({"height": 4.0, "max_width": 0.5}, "max_width:"), ({"height": 4.0, "max_width": 1e6}, "max_width:"),
    ({"height": 4.0, "courses": 0}, "courses:"), ({"height": 4.0, "batter": -1.0}, "batter:"),
])
def test_bad_inputs_by_name(kwargs, start):
    with pytest.raises(ArchInputError, match="^" + start):
        minimum_pier_width(ARCH, **kwargs)
    with pytest.raises(ArchInputError, match="^arch: already on piers"):
        minimum_pier_width(with_piers(ARCH, 4.0, 2.0), 4.0)


def test_trusted_rebuild_is_the_checked_one():
    poly = _as_polygon(ARCH)
    a = with_piers(poly, 4.0, 1.3, courses=3, batter=0.05, _trusted=True)
    b = with_piers(poly, 4.0, 1.3, courses=3, batter=0.05)
    assert np.array_equal(a.masses, b.masses) and np.array_equal(a.centroids, b.centroids)
    assert np.array_equal(a.joint_points, b.joint_points) and a.block_kinds == b.block_kinds


# ------------------------------------------------------------------------- k against height
def test_k_against_pier_height():
    heights = [0.0, 2.0, 4.0, 10.0]
    t = k_against_pier_height(ARCH, 2.0, heights)
    assert t.heights.tolist() == heights and t.span == pytest.approx(9.2, abs=1e-12)
    rigid = limit_analysis(ARCH)
    assert t.k_l[0] == rigid.k_l and t.labels_l[0] == rigid.mechanism_l.label
    assert t.k_l[2] == pytest.approx(0.168899, abs=1e-6)
    assert t.places_l[2] == "right pier foot, outer face"
    assert np.all(np.diff(t.k[1:]) < 0)         # taller piers, lower k
    assert np.allclose(t.k_l, t.k_r, rtol=1e-9)
    d = json.loads(json.dumps(t.to_dict()))
    assert d["rows"][2]["height_over_span"] == pytest.approx(4.0 / 9.2)
    with pytest.raises(ArchInputError, match="^heights:"):
        k_against_pier_height(ARCH, 2.0, [-1.0])
    with pytest.raises(ArchInputError, match="^heights:"):
        k_against_pier_height(ARCH, 2.0, [])


# ------------------------------------------------------------------------- friction on piers
def test_rocking_frame_slides_at_its_bases_by_hand(rocking_frame):
    """Two columns under a beam (the rocking frame as an arch on piers): with friction mu below
    tan(alpha) = b / h the frame slides. By hand: across any horizontal section (the column
    feet, the beam's seats) the shears carry lambda W_above and the normal forces W_above, so
    lambda <= mu, and the rigid sliding of the whole frame on its two feet attains it: k = mu,
    with |T|/N = mu at the pier bases (joints 0 and 3) and at the seats."""
    frame = rocking_frame(0.3, 1.2, 0.3)
    data = frame.to_dict()
    for v, k in zip(data["voussoirs"], ("pier", "voussoir", "pier")):
        v["kind"] = k
    frame = arch_from_dict(data)
    assert frame.pier_blocks == (0, 2)
    k0 = limit_analysis(frame).k_l
    assert k0 == pytest.approx(0.25, rel=1e-9)
    for mu in (0.05, 0.15):
        f = friction_analysis(frame, mu)
        for d in (f.l, f.r):
            assert d.multiplier == pytest.approx(mu, rel=1e-9)
            assert d.sliding_governs and d.frictionless == pytest.approx(k0, rel=1e-9)
            assert 0 in d.joints and 3 in d.joints
            assert d.ratios[[0, 3]] == pytest.approx([mu, mu], rel=1e-6)
    f = friction_analysis(frame, 0.4)            # more friction than rocking needs
    assert f.l.multiplier == pytest.approx(0.25, rel=1e-9) and not f.l.sliding_governs
    assert friction_needed(frame)["l"] == pytest.approx(0.25, rel=1e-9)


def test_semicircle_on_piers_with_friction(capsys):
    """The reference semicircle on piers (4 x 2 m, 2 courses): the no-sliding collapse needs
    mu = 0.5045 (at the far springing, joint 11); below it the arch slides outward on the far
    pier's top (k 0.0699 at mu = 0.4, 0.1645 at 0.5). Whole-structure sliding on both pier
    feet (lambda = mu) is an upper bound that an arch never reaches: it needs the near pier
    pulled inward by the arch (negative thrust)."""
    ap = with_piers(ARCH, 4.0, 2.0, courses=2)
    need = friction_needed(ap)
    assert need["l"] == pytest.approx(0.504523, abs=1e-6)
    for mu, k in ((0.4, 0.069873), (0.5, 0.164499)):
        f = friction_analysis(ap, mu)
        assert f.l.multiplier == pytest.approx(k, abs=1e-6)
        assert f.l.sliding_governs and f.l.joints == (11,)
        assert f.l.ratios[11] == pytest.approx(mu, rel=1e-6)
        assert f.l.multiplier < mu
    code = main(["limit", "--radius", "5", "--embrace", "180", "--thickness", "0.8",
                 "--voussoirs", "9", "--pier-height", "4", "--pier-width", "2",
                 "--pier-courses", "2", "--friction", "0.4", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["friction_k_l"] == pytest.approx(0.069873, abs=1e-6)
    assert out["friction_joints_l"] == [11]
