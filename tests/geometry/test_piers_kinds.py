"""Arches on piers, issue 19 parts 1 and 2: block kinds read back from geometry files (to the
bit), refused by name; hinges named on the drawing ("left pier foot, outer face") in the text and
JSON reports and in the figures; per-side piers and battered piers (buttresses): zero batter is
the rectangular pier bit for bit, mass and centroid against the trapezoid's formulas."""

from __future__ import annotations

import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.errors import ArchInputError
from archrock.geometry import ArchOnPiers, Load, PolygonArch, arch_from_dict, nominal_arch, with_piers
from archrock.geometry.files import read_arch, write_arch
from archrock.geometry.piers import hinge_place, joint_place
from archrock.statics.limit import limit_analysis

ARCH = nominal_arch(radius=5.0, embrace_deg=180, thickness=0.8, voussoirs=9)
BASE = ("--radius", "5", "--embrace", "180", "--thickness", "0.8", "--voussoirs", "9")


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _same(a, b):
    assert type(a) is type(b)
    assert a.n == b.n and a.density == b.density and a.loads == b.loads
    assert all(np.array_equal(p, q) for p, q in zip(a.intrados, b.intrados))
    assert all(np.array_equal(p, q) for p, q in zip(a.extrados, b.extrados))
    assert np.array_equal(a.masses, b.masses) and np.array_equal(a.centroids, b.centroids)


# ------------------------------------------------------------------------- kinds read back
@pytest.mark.parametrize("kwargs", [{"courses": 3, "courses_right": 2},
                                    {"batter": 0.15, "courses": 2, "width_right": 2.5}])
def test_kinds_round_trip_to_the_bit(tmp_path, kwargs):
    a = ARCH
    loaded = type(a)(a.spans, a.radii, a.thicknesses, a.density, "loaded",
                     (Load(4, 3000.0, (0.0, 5.5)),))
    ap = with_piers(loaded, 4.0, 2.0, **kwargs)
    path = write_arch(ap, tmp_path / "piers.json")
    back = read_arch(path)
    _same(back, ap)
    assert back.block_kinds == ap.block_kinds and back.pier_blocks == ap.pier_blocks
    assert back.to_dict() == ap.to_dict()
    assert limit_analysis(back).k_l == limit_analysis(ap).k_l
    # and a dict without kinds stays a plain PolygonArch
    plain = ap.to_dict()
    for v in plain["voussoirs"]:
        del v["kind"]
    assert type(arch_from_dict(plain)) is PolygonArch


def test_partial_kinds_default_to_voussoir():
    data = with_piers(ARCH, 4.0, 2.0).to_dict()
    del data["voussoirs"][5]["kind"]
    back = arch_from_dict(data)
    assert isinstance(back, ArchOnPiers) and back.block_kinds[5] == "voussoir"
    assert back.pier_blocks == (0, back.n - 1)


@pytest.mark.parametrize("kind", ["wall", "Pier", 3, None, ["pier"]])
def test_bad_kind_refused_by_name(tmp_path, kind):
    data = with_piers(ARCH, 4.0, 2.0).to_dict()
    data["voussoirs"][2]["kind"] = kind
    with pytest.raises(ArchInputError, match=r"^voussoirs\[2\]\.kind: .*allowed pier, voussoir, "
                                             r"buttress"):
        arch_from_dict(data)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data))
    with pytest.raises(ArchInputError, match=r"bad\.json: voussoirs\[2\]\.kind:"):
        read_arch(path)


def test_mirrored_and_scaled_keep_kinds():
    ap = with_piers(ARCH, 4.0, 2.0, courses=3, courses_right=1, batter_right=0.2)
    m = ap.mirrored()
    assert isinstance(m, ArchOnPiers)
    assert m.block_kinds == ap.block_kinds[::-1] == ("buttress",) + ("voussoir",) * 9 + ("pier",) * 3
    assert m.piers == ((0,), (10, 11, 12))
    s = ap.scaled(2.0)
    assert s.block_kinds == ap.block_kinds
    assert s.masses.sum() == pytest.approx(4 * ap.masses.sum(), rel=1e-12)


def test_joint_and_hinge_places():
    """Every joint of a chain with 3 courses on the left and 2 on the right, in words."""
    ap = with_piers(ARCH, 4.0, 2.0, courses=3, courses_right=2)
    n = ap.n
    assert n == 14
    want = ["left pier foot", "left pier bed joint 1", "left pier bed joint 2",
            "left springing (pier top)"] + [f"arch joint {k}" for k in range(1, 9)] + \
        ["right springing (pier top)", "right pier bed joint 1", "right pier foot"]
    assert [joint_place(ap, j) for j in range(n + 1)] == want
    assert hinge_place(ap, 0, "extrados") == "left pier foot, outer face"
    assert hinge_place(ap, 14, "intrados") == "right pier foot, inner face"
    assert hinge_place(ap, 13, "extrados") == "right pier bed joint 1, outer face"
    assert hinge_place(ap, 3, "intrados") == "left springing (pier top), intrados"
    assert hinge_place(ap, 6, "extrados") == "arch joint 3, extrados"
    assert joint_place(ARCH, 4) == "joint 4" and hinge_place(ARCH, 4, "intrados") == \
        "joint 4, intrados"
    bt = with_piers(ARCH, 4.0, 2.0, batter=0.1)
    assert hinge_place(bt, 0, "extrados") == "left buttress foot, outer face"


# ------------------------------------------------------------------------- reports
def test_limit_report_names_piers_and_hinges(capsys):
    code, out, err = run(capsys, "limit", *BASE, "--pier-height", "4", "--pier-width", "2",
                         "--pier-courses", "2")
    assert code == 0, err
    # blocks by kind: two piers of two courses, not "4 piers" (issue 30)
    assert "13 blocks: 9 voussoirs on two piers (2 courses each); ArchOnPiers" in out
    rows = [ln.split() for ln in out.splitlines() if ln[:7].strip().isdigit()]
    assert [r[1] for r in rows] == ["pier"] * 2 + ["voussoir"] * 9 + ["pier"] * 2
    assert "D = 13e (right pier foot, outer face)" in out
    assert "D = 0e (left pier foot, outer face)" in out
    code, out, err = run(capsys, "limit", *BASE, "--pier-height", "4", "--pier-width", "2",
                         "--pier-courses", "2", "--json")
    d = json.loads(out)
    assert d["block_kinds"] == ["pier"] * 2 + ["voussoir"] * 9 + ["pier"] * 2
    assert [v["kind"] for v in d["voussoirs"]] == d["block_kinds"]
    assert d["blocks"] == {"voussoirs": 9, "pier_blocks": 4, "buttress_blocks": 0, "piers": 2,
                           "blocks": 13}
    assert [v["kind"] for v in d["geometry"]["voussoirs"]] == d["block_kinds"]
    last = d["hinge_labels"]["l"][-1]
    assert last == {"label": "D", "joint": 13, "edge": "extrados",
                    "place": "right pier foot, outer face"}
    # an arch without piers: no kinds, no places (the report as before)
    code, out, err = run(capsys, "limit", *BASE, "--json")
    d = json.loads(out)
    assert "block_kinds" not in d and all("place" not in h for h in d["hinge_labels"]["l"])


def test_figure_draws_piers_and_the_thrust_through_them():
    pytest.importorskip("matplotlib")
    from matplotlib.colors import to_hex

    from archrock.reports.plots import STYLE, draw_arch, new_figure, plot_limit

    ap = with_piers(ARCH, 4.0, 2.0, courses=2, batter=0.1, batter_right=0.0)
    fig, axes = new_figure(1, 2)
    patches = draw_arch(axes[0][0], ap)
    faces = [to_hex(p.get_facecolor()) for p in patches]
    assert faces == [STYLE["buttress_face"]] * 2 + [STYLE["voussoir_face"]] * 9 + \
        [STYLE["pier_face"]] * 2
    res = limit_analysis(ap)
    ax = plot_limit(res, "l", ax=axes[0][1])
    assert {"pier", "buttress"} <= {t.get_text() for t in ax.get_legend().get_texts()}
    assert "D: right pier foot, outer face" in ax.get_title()
    line = next(ln for ln in ax.get_lines() if ln.get_label() == "line of thrust at collapse")
    xy = np.column_stack(line.get_data())
    foot = ap.joint_point(res.mechanism_l.hinges[-1].joint, "extrados")
    assert res.mechanism_l.hinges[-1].joint == ap.n
    # the thrust line ends at the pier's outer foot corner and runs down through the piers
    assert np.min(np.hypot(*(xy - foot).T)) < 1e-9
    assert xy[:, 1].min() == pytest.approx(-4.0, abs=1e-9)


# ------------------------------------------------------------------------- per side, batter
def test_zero_batter_is_the_rectangular_pier_bit_for_bit():
    for kw in ({}, {"courses": 3, "courses_right": 2, "height_right": 5.0, "width_right": 2.5}):
        rect = with_piers(ARCH, 4.0, 2.0, **kw)
        zero = with_piers(ARCH, 4.0, 2.0, batter=0.0, batter_right=0.0, **kw)
        _same(zero, rect)
        assert zero.block_kinds == rect.block_kinds
        assert limit_analysis(zero).k_l == limit_analysis(rect).k_l
    # also on a segmental arch, whose top course carries the springing wedge
    seg = nominal_arch(radius=10.0, embrace_deg=120, thickness=1.0, voussoirs=7)
    _same(with_piers(seg, 5.0, 3.0, courses=2, batter=0), with_piers(seg, 5.0, 3.0, courses=2))


@pytest.mark.parametrize("b,courses", [(0.1, 1), (0.25, 1), (0.25, 4), (2.0, 1)])
def test_battered_pier_mass_and_centroid_are_the_trapezoids(b, courses):
    """A battered monolithic pier (or its courses together) is a trapezoid: top width W, base
    W + b H, height H; area H (2W + b H)/2; centroid at H (a + 2c)/(3 (a + c)) above the base
    (a, c: base and top widths) and, outward of the inner face, ((W + b H)^3 - W^3)/(6 b A)."""
    H, W, rho = 4.0, 2.0, 2000.0
    ap = with_piers(ARCH, H, W, courses=courses, batter=b, batter_right=0.0)
    left = list(ap.piers[0])
    assert ap.block_kinds[:courses] == ("buttress",) * courses
    assert ap.block_kinds[-1] == "pier"
    a, c = W + b * H, W
    area = H * (a + c) / 2
    m = ap.masses[left]
    assert m.sum() == pytest.approx(rho * area, rel=1e-12)
    cen = (m[:, None] * ap.centroids[left]).sum(axis=0) / m.sum()
    xi, top = -4.6, 0.0
    assert cen[1] - (top - H) == pytest.approx(H * (a + 2 * c) / (3 * (a + c)), rel=1e-12)
    u = ((W + b * H) ** 3 - W ** 3) / (6 * b * area)
    assert xi - cen[0] == pytest.approx(u, rel=1e-12)
    # the foundation joint is the base width, the top joint (springing) the arch's own face
    assert ap.joint_points[0][:, 0] == pytest.approx([xi, xi - a], abs=1e-12)
    # the right pier is the rectangle still
    assert ap.masses[list(ap.piers[1])].sum() == pytest.approx(rho * H * W, rel=1e-12)


def test_a_batter_stiffens_the_piers():
    """Wider at the foot, the pier's outer foot corner moves out: k rises with the batter, hinge
    D at the far pier's outer foot, until the hinge moves to the springing (batter 0.01 here):
    then k is the arch's own on rigid ground (0.174779; the arch as polygons, arc step 0.002
    rad, to 4e-7)."""
    ks = [limit_analysis(with_piers(ARCH, 4.0, 2.0, batter=b)) for b in (0.0, 0.005, 0.01, 0.05)]
    assert ks[0].k_l == pytest.approx(0.168899, abs=1e-6)
    assert ks[1].k_l == pytest.approx(0.173597, abs=1e-6)
    assert ks[0].k_l < ks[1].k_l < ks[2].k_l
    for r in ks[:2]:
        assert r.mechanism_l.label == "2i-5e-8i-11e"        # D: the right buttress's outer foot
    rigid = limit_analysis(ARCH).k_l
    for r in ks[2:]:
        assert r.mechanism_l.label == "2i-5e-8i-10e"        # D: the right springing, extrados
        assert r.k_l == pytest.approx(rigid, rel=1e-6)


def test_cli_right_pier_and_batter_flags(capsys):
    code, out, err = run(capsys, "limit", *BASE, "--pier-height", "4", "--pier-width", "2",
                         "--pier-courses", "2", "--right-pier-height", "6", "--right-pier-width",
                         "2.5", "--right-pier-courses", "3", "--pier-batter", "0.1",
                         "--right-pier-batter", "0", "--json")
    assert code == 0, err
    lib = limit_analysis(with_piers(ARCH, 4.0, 2.0, courses=2, height_right=6.0, width_right=2.5,
                                    courses_right=3, batter=0.1, batter_right=0.0))
    d = json.loads(out)
    assert d["k_l"] == lib.k_l and d["k_r"] == lib.k_r
    assert d["block_kinds"] == ["buttress"] * 2 + ["voussoir"] * 9 + ["pier"] * 3
    assert d["geometry"]["voussoirs"][-1]["intrados"][-1] == [4.6, -6.0]


@pytest.mark.parametrize("extra,start", [
    (("--right-pier-width", "2"), "archrock: error: --pier-height and --pier-width: needed with "
                                  "--right-pier-width"),
    (("--pier-batter", "0.1"), "archrock: error: --pier-height and --pier-width: needed with "
                               "--pier-batter"),
    (("--pier-height", "4", "--pier-width", "2", "--pier-batter", "-0.1"),
     "archrock: error: --pier-batter: -0.1 is out of range; allowed 0 <= batter <= 10"),
    (("--pier-height", "4", "--pier-width", "2", "--right-pier-batter", "11"),
     "archrock: error: --right-pier-batter:"),
    (("--pier-height", "4", "--pier-width", "2", "--right-pier-width", "0.5"),
     "archrock: error: --right-pier-width:"),
    (("--pier-height", "4", "--pier-width", "2", "--right-pier-height", "0"),
     "archrock: error: --right-pier-height:"),
    (("--pier-height", "4", "--pier-width", "2", "--right-pier-courses", "0"),
     "archrock: error: --right-pier-courses:"),
])
def test_cli_right_pier_flags_refused_by_name(capsys, extra, start):
    code, out, err = run(capsys, "limit", *BASE, *extra)
    assert code == 2 and err.startswith(start), err


def test_bad_batter_by_name():
    for kw, field in (({"batter": -0.1}, "batter:"), ({"batter": "0.1"}, "batter:"),
                      ({"batter": float("nan")}, "batter:"), ({"batter_right": 10.5}, "batter_right:"),
                      ({"batter": True}, "batter:")):
        with pytest.raises(ArchInputError, match="^" + field):
            with_piers(ARCH, 4.0, 2.0, **kw)
