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
    assert "13 blocks (4 piers, 9 voussoirs" in out
    rows = [ln.split() for ln in out.splitlines() if ln[:7].strip().isdigit()]
    assert [r[1] for r in rows] == ["pier"] * 2 + ["voussoir"] * 9 + ["pier"] * 2
    assert "D = 13e (right pier foot, outer face)" in out
    assert "D = 0e (left pier foot, outer face)" in out
    code, out, err = run(capsys, "limit", *BASE, "--pier-height", "4", "--pier-width", "2",
                         "--pier-courses", "2", "--json")
    d = json.loads(out)
    assert d["block_kinds"] == ["pier"] * 2 + ["voussoir"] * 9 + ["pier"] * 2
    assert [v["kind"] for v in d["voussoirs"]] == d["block_kinds"]
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
