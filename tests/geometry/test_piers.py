"""Arches on piers (archrock.geometry.with_piers, --pier-height/--pier-width): the rocking frame
of Makris & Vassiliou (2013) against its closed forms (activation and frequency parameter), a
semicircle on piers from with_piers, from the command-line flags and from a hand-written geometry
file, the heavy-pier case of issue 19, and bad inputs by name."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from archrock.cli import main
from archrock.errors import ArchInputError
from archrock.geometry.files import read_arch, write_arch
from archrock.geometry import (Arch, ArchOnPiers, Load, PolygonArch, arch_from_dict, family_arch,
                               nominal_arch, with_piers)
from archrock.statics.limit import limit_analysis
from archrock.dynamics.fourlink import four_link
from archrock.units import G


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# ------------------------------------------------------------------------- the rocking frame


FRAMES = [(0.25, 1.0, 0.3, ()), (0.5, 1.5, 0.05, ()), (0.2, 2.5, 0.6, ()),
          (0.3, 1.2, 0.2, (Load(1, 5.0e4, (2.0, 2.5)),)),     # a heavy load off the beam's middle
          (0.3, 1.2, 0.2, (Load(1, 1.0, (4.5, 2.45)),))]


@pytest.mark.parametrize("b,h,depth,loads", FRAMES)
def test_rocking_frame_activation_is_tan_alpha(b, h, depth, loads, rocking_frame):
    """Static activation of the frame: tan(alpha) = b/h of one column, whatever the beam's mass
    (Makris & Vassiliou 2013), by the limit analysis (kinematic and static), with the four
    hinges at the columns' corners: M_l rocks both columns on their right foot corners
    (intrados of joints 0 and 2) and hinges them at their top-left corners (extrados 1, 3)."""
    frame = rocking_frame(b, h, depth, loads=loads)
    res = limit_analysis(frame)
    for k in (res.k_l, res.k_r, res.static_k_l, res.static_k_r):
        assert k == pytest.approx(b / h, rel=1e-9)
    assert res.mechanism_l.kind == res.mechanism_r.kind == "four-hinge"
    assert res.mechanism_l.label == "0i-1e-2i-3e"
    assert res.mechanism_r.label == "0e-1i-2e-3i"


@pytest.mark.parametrize("b,h,depth,loads", FRAMES)
def test_rocking_frame_frequency_parameter(b, h, depth, loads, rocking_frame):
    """The four-link model of the limit analysis's mechanism (M phi'' + L phi'^2 + F g = P xg''):
    M(0) and the restoring moment F(phi) = s sin(alpha - phi) give Housner's
    phi'' = -p^2 sin(alpha - phi) with p^2 = g F(0) / (M(0) sin(alpha)) = -g F'(0) /
    (M(0) cos(alpha)) = (3 g / 4R)(1 + 2 gamma)/(1 + 3 gamma) (Makris & Vassiliou 2013),
    gamma = beam mass (with its loads) / both columns' mass, R = sqrt(b^2 + h^2)."""
    frame = rocking_frame(b, h, depth, loads=loads)
    res = limit_analysis(frame)
    m = frame.masses[0]
    gamma = frame.masses[1] / (frame.masses[0] + frame.masses[2])
    R, alpha = math.hypot(b, h), math.atan2(b, h)
    closed = 3 * G / (4 * R) * (1 + 2 * gamma) / (1 + 3 * gamma)
    assert gamma > 0
    for mech in (res.mechanism_l, res.mechanism_r):
        fl = four_link(frame, mech)
        M0, L0, F0, P0 = fl.coefficients(0.0)
        assert abs(L0) < 1e-9 * M0
        assert M0 == pytest.approx(8 / 3 * m * R * R * (1 + 3 * gamma), rel=1e-9)
        assert G * F0 / (M0 * math.sin(alpha)) == pytest.approx(closed, rel=1e-6)
        d = 1e-6
        dF = (fl.coefficients(d)[2] - fl.coefficients(-d)[2]) / (2 * d)
        assert -G * dF / (M0 * math.cos(alpha)) == pytest.approx(closed, rel=1e-6)
    if loads and loads[0].mass > 1e4:
        assert closed == pytest.approx(3 * G / (4 * R) * 2 / 3, rel=0.05)   # gamma -> infinity


# ------------------------------------------------------------------------- construction
def test_semicircle_on_piers_blocks_and_joints():
    """Chain order, kinds, joint numbering and masses of a semicircle on two piers of 3 and 2
    courses: left pier from the foundation (joint 0) up, the voussoirs, right pier top down."""
    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    ap = with_piers(arch, 4.0, 2.0, courses=3, courses_right=2)
    assert isinstance(ap, ArchOnPiers) and ap.n == 9 + 5
    assert ap.block_kinds == ("pier",) * 3 + ("voussoir",) * 9 + ("pier",) * 2
    assert ap.pier_blocks == (0, 1, 2, 12, 13)
    jp = ap.joint_points
    # foundations 4 m below the springing (y = 0), bed joints horizontal, every 4/3 and 2 m
    assert jp[0] == pytest.approx(np.array([[-4.6, -4.0], [-6.6, -4.0]]), abs=1e-12)
    assert jp[-1] == pytest.approx(np.array([[4.6, -4.0], [6.6, -4.0]]), abs=1e-12)
    for j, y in ((1, -8 / 3), (2, -4 / 3), (13, -2.0)):
        assert jp[j][:, 1] == pytest.approx([y, y], abs=1e-12)
    # the springing joints: the arch's own faces (0.8 m), on the pier tops
    assert jp[3] == pytest.approx(np.array([[-4.6, 0.0], [-5.4, 0.0]]), abs=1e-9)
    assert jp[12] == pytest.approx(np.array([[4.6, 0.0], [5.4, 0.0]]), abs=1e-9)
    pier = 2000.0 * 2.0 * 4.0
    assert ap.masses[:3].sum() == pytest.approx(pier, rel=1e-12)
    assert ap.masses[12:].sum() == pytest.approx(pier, rel=1e-12)
    ring = 2000.0 * math.pi / 2 * (5.4 ** 2 - 4.6 ** 2)
    assert ap.masses[3:12].sum() == pytest.approx(ring, rel=1e-6)
    # to_dict names the kinds and reads back (an ArchOnPiers) with the same blocks
    data = ap.to_dict()
    assert [v["kind"] for v in data["voussoirs"]] == list(ap.block_kinds)
    back = arch_from_dict(json.loads(json.dumps(data)))
    assert back.n == ap.n
    assert np.array_equal(back.joint_points, ap.joint_points)
    assert np.array_equal(back.masses, ap.masses)


def test_segmental_arch_gets_a_springing_wedge():
    """A segmental arch (radial springing joints, tilted): the top course carries the wedge up to
    the springing joint, its bed joints horizontal; its area is the rectangle plus the triangle
    between the pier top (at the joint's intrados end), the joint and the vertical through the
    extrados end."""
    arch = nominal_arch(radius=10.0, embrace_deg=120, thickness=1.0, voussoirs=7)
    ap = with_piers(arch, 5.0, 3.0, courses=2)
    (xi, yi), (xe, ye) = arch.joint_points[0]
    assert ye > yi
    assert ap.joint_points[0][:, 1] == pytest.approx([yi - 5.0] * 2, abs=1e-12)
    assert ap.joint_points[1][:, 1] == pytest.approx([yi - 2.5] * 2, abs=1e-12)
    assert ap.joint_points[2] == pytest.approx(arch.joint_points[0], abs=1e-9)
    assert ap.areas[0] == pytest.approx(7.5, rel=1e-12)
    assert ap.areas[1] == pytest.approx(7.5 + 0.5 * (xi - xe) * (ye - yi), rel=1e-12)
    assert ap.areas[-2] == pytest.approx(ap.areas[1], rel=1e-12)   # the right top course
    assert ap.areas[-1] == pytest.approx(7.5, rel=1e-12)
    res = limit_analysis(ap)
    assert res.k_l == pytest.approx(res.k_r, rel=1e-9)
    assert res.discrepancy < 1e-9


def test_loads_follow_their_voussoir():
    a = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    arch = Arch(a.spans, a.radii, a.thicknesses, a.density, "loaded", (Load(4, 3000.0, (0.0, 5.5)),))
    ap = with_piers(arch, 4.0, 2.0, courses=2)
    assert ap.loads == (Load(6, 3000.0, (0.0, 5.5)),)


# ------------------------------------------------------------------------- the reference case
def _hand_written(R, t, n, H, W, per=120):
    """The semicircle of mean radius R on piers H x W, written out by hand as polygon blocks."""
    ri, ro = R - t / 2, R + t / 2
    blocks = [{"intrados": [[-ri, -H], [-ri, 0.0]], "extrados": [[-ri - W, -H], [-ri - W, 0.0]]}]
    for i in range(n):
        ang = np.linspace(math.pi * (1 - i / n), math.pi * (1 - (i + 1) / n), per)
        blocks.append({"intrados": np.column_stack([ri * np.cos(ang), ri * np.sin(ang)]).tolist(),
                       "extrados": np.column_stack([ro * np.cos(ang), ro * np.sin(ang)]).tolist()})
    blocks.append({"intrados": [[ri, 0.0], [ri, -H]], "extrados": [[ri + W, 0.0], [ri + W, -H]]})
    return {"voussoirs": blocks, "density": 2000.0}


def test_semicircle_on_piers_three_ways(tmp_path, capsys):
    """Issue 19's reference: a semicircle of 10 m span (of the centreline: R = 5 m), t = 0.8 m,
    9 voussoirs, on piers 4 m high and 2 m wide: k = 0.1689, hinges 2i-5e-8i-11e (M_l; D at the
    right pier's outer foot), the same from with_piers, from a hand-written geometry file and
    from the flags."""
    arch = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
    res = limit_analysis(with_piers(arch, 4.0, 2.0))
    path = tmp_path / "semicircle_on_piers.json"
    path.write_text(json.dumps(_hand_written(5.0, 0.8, 9, 4.0, 2.0)))
    hand = limit_analysis(read_arch(path))
    assert res.k_l == pytest.approx(0.168899, abs=1e-6)
    assert res.k_l == pytest.approx(res.k_r, rel=1e-9)
    assert hand.k_l == pytest.approx(res.k_l, rel=1e-7)     # measured 4.4e-9
    assert hand.k_r == pytest.approx(res.k_r, rel=1e-7)
    assert res.mechanism_l.label == hand.mechanism_l.label == "2i-5e-8i-11e"
    assert res.mechanism_r.label == hand.mechanism_r.label == "0e-3i-6e-9i"
    assert res.discrepancy < 1e-9 and hand.discrepancy < 1e-9
    code, out, err = run(capsys, "limit", "--radius", "5", "--embrace", "180", "--thickness", "0.8",
                         "--voussoirs", "9", "--pier-height", "4", "--pier-width", "2", "--json")
    assert code == 0, err
    flags = json.loads(out)
    assert flags["k"] == pytest.approx(res.k_l, rel=1e-12)
    assert flags["mechanism_l"]["label"] == "2i-5e-8i-11e"
    code, out, err = run(capsys, "limit", "--geometry", str(path), "--json")
    assert code == 0, err
    assert json.loads(out)["k"] == pytest.approx(flags["k"], rel=1e-7)
    # the intrados span convention instead (R = 5.4 m) gives another arch: 0.1401
    other = limit_analysis(with_piers(nominal_arch(radius=5.4, embrace_deg=180, thickness=0.8,
                                                   voussoirs=9), 4.0, 2.0))
    assert other.k_l == pytest.approx(0.1401, abs=1e-4)
    # courses do not change it here: the hinges are at the pier tops and feet
    four = limit_analysis(with_piers(arch, 4.0, 2.0, courses=4))
    assert four.k_l == pytest.approx(res.k_l, rel=1e-9)
    # written by write_arch (with kinds) and read back: the same k to the bit
    write_arch(with_piers(arch, 4.0, 2.0), tmp_path / "w.json")
    assert limit_analysis(read_arch(tmp_path / "w.json")).k_l == res.k_l


def test_family_arch_on_piers():
    """A pointed family arch (polygon) on unequal piers: kinematic = static."""
    arch = family_arch("pointed", 10.0, 7.0, 1.0, 12)
    ap = with_piers(arch, 3.0, 2.0, courses=3, height_right=5.0, width_right=2.5)
    assert ap.joint_points[0][0][1] == pytest.approx(-3.0, abs=1e-12)
    assert ap.joint_points[-1][0][1] == pytest.approx(-5.0, abs=1e-12)
    res = limit_analysis(ap)
    assert res.discrepancy < 1e-9
    assert 0 < min(res.k_l, res.k_r) < limit_analysis(arch).k


def test_heavy_piers_case(heavy_piers_file):
    """tests/data/heavy_piers.json (12 voussoirs on two 30 m piers 5 m wide, the springing
    wedge in the pier's block): the limit analysis gives the four-link activation of its
    metadata, 0.1131 (measured 0.113071), D at the right pier's outer foot."""
    arch = read_arch(heavy_piers_file)
    meta = json.loads(heavy_piers_file.read_text())["metadata"]
    assert "0.1131" in meta["measured"]
    res = limit_analysis(arch)
    assert res.k_l == pytest.approx(0.1131, abs=5e-5)
    assert res.k_l == pytest.approx(0.113071, abs=1e-6)
    assert res.k_r == pytest.approx(res.k_l, rel=1e-9)
    assert res.mechanism_l.kind == "four-hinge"
    assert res.mechanism_l.label == "1i-6e-12i-14e"
    assert res.discrepancy < 1e-9


# ------------------------------------------------------------------------- bad inputs
ARCH = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)


@pytest.mark.parametrize("kwargs,field", [
    ({"height": 0.0, "width": 2.0}, "height:"), ({"height": -1.0, "width": 2.0}, "height:"),
    ({"height": math.nan, "width": 2.0}, "height:"), ({"height": 4.0, "width": 0.0}, "width:"),
    ({"height": 4.0, "width": math.inf}, "width:"), ({"height": 4.0, "width": "2"}, "width:"),
    ({"height": 4.0, "width": 0.5}, "width:"), ({"height": 4.0, "width": 2.0, "courses": 0}, "courses:"),
    ({"height": 4.0, "width": 2.0, "courses": 201}, "courses:"),
    ({"height": 4.0, "width": 2.0, "courses": 1.5}, "courses:"),
    ({"height": 4.0, "width": 2.0, "courses": True}, "courses:"),
    ({"height": 4.0, "width": 2.0, "courses_right": -2}, "courses_right:"),
    ({"height": 4.0, "width": 2.0, "height_right": 0.0}, "height_right:"),
    ({"height": 4.0, "width": 2.0, "width_right": 0.3}, "width_right:"),
    ({"height": 1e9, "width": 2.0}, "height:"),
])
def test_bad_inputs_by_name(kwargs, field):
    with pytest.raises(ArchInputError, match="^" + field):
        with_piers(ARCH, **kwargs)


def test_bad_arch_by_name():
    with pytest.raises(ArchInputError, match="^arch:"):
        with_piers({"voussoirs": []}, 4.0, 2.0)
    with pytest.raises(ArchInputError, match="^arch: already on piers"):
        with_piers(with_piers(ARCH, 4.0, 2.0), 4.0, 2.0)


def test_cli_pier_flags_refused_by_name(capsys):
    base = ("limit", "--radius", "5", "--embrace", "180", "--thickness", "0.8", "--voussoirs", "9")
    for extra, start in ((("--pier-width", "2"), "archrock: error: --pier-height:"),
                         (("--pier-courses", "2"), "archrock: error: --pier-height and --pier-width:"),
                         (("--pier-height", "4", "--pier-width", "0.5"), "archrock: error: --pier-width:"),
                         (("--pier-height", "0", "--pier-width", "2"), "archrock: error: --pier-height:"),
                         (("--pier-height", "4", "--pier-width", "2", "--pier-courses", "0"),
                          "archrock: error: --pier-courses:")):
        code, out, err = run(capsys, *base, *extra)
        assert code == 2 and err.startswith(start), err
