"""Defects (archrock.geometry.defect), defect maps (archrock.studies.defectmap) and `archrock defects`."""

import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.studies.defectmap import defect_map
from archrock.studies.runner import RunSettings
from archrock.errors import ArchInputError
from archrock.geometry import (Arch, Defect, PolygonArch, apply_defect, as_polygon, family_arch,
                               oppenheim_arch)
from archrock.statics.limit import limit_analysis

K_OPP = 0.3700097380218764


# ---------------------------------------------------------------------------- parsing
@pytest.mark.parametrize("text, expect", [
    ("3:thickness=0.7", Defect("thickness", 3, 0.7, "centreline")),
    ("0:thickness=0.5,at=intrados", Defect("thickness", 0, 0.5, "intrados")),
    (" 2 : thickness = 0.9 , at=extrados", Defect("thickness", 2, 0.9, "extrados")),
    ("4:tilt=-5", Defect("tilt", 4, -5.0)),
    ("7:mortar=0.2,from=extrados", Defect("mortar", 7, 0.2, "extrados")),
    ("7:mortar=0.2,side=extrados", Defect("mortar", 7, 0.2, "extrados")),
    ("1:thickness=0.5,side=intrados", Defect("thickness", 1, 0.5, "intrados")),
    ("1:mortar=0.2", Defect("mortar", 1, 0.2, "intrados")),
])
def test_parse_and_round_trips(text, expect):
    d = Defect.parse(text)
    assert d == expect
    assert Defect.parse(d.spec()) == d
    assert Defect.from_dict(json.loads(json.dumps(d.to_dict()))) == d


@pytest.mark.parametrize("text, words", [
    ("3:thickness=1.2", ["thickness", "0 < value < 1"]),
    ("3:thickness=0", ["thickness", "0 < value < 1"]),
    ("3:tilt=50", ["tilt", "-45 < tilt < 45"]),
    ("3:mortar=1", ["mortar", "0 < value < 1"]),
    ("7:thickness=0.7", ["voussoir", "0..6"]),
    ("8:tilt=5", ["joint", "0..7"]),
    ("x:tilt=5", ["joint", "integer"]),
    ("3:crack=0.5", ["kind", "thickness, tilt, mortar"]),
    ("3:thickness=0.7,at=middle", ["side", "centreline, intrados, extrados"]),
    ("3:thickness=0.7,side=middle", ["side", "centreline, intrados, extrados"]),
    ("3:mortar=0.2,at=extrados", ["side="]),
    ("4:tilt=5,side=intrados", ["none for a tilt"]),
    ("3:thickness=abc", ["thickness", "0 < value < 1"]),
    ("thickness", ["defect", "VOUSSOIR:thickness"]),
])
def test_bad_specs_name_the_field_and_range(text, words):
    with pytest.raises(ArchInputError) as e:
        apply_defect(oppenheim_arch(), text)
    for w in words:
        assert w in str(e.value)


# ---------------------------------------------------------------------------- geometry
def test_thickness_loss_on_a_circular_arch_is_an_exact_sector():
    a = oppenheim_arch()
    for at, (ri, ro) in {"centreline": (9.475, 10.525), "intrados": (9.7, 10.75),
                         "extrados": (9.25, 10.3)}.items():
        b = apply_defect(a, Defect.thickness(2, 0.7, at))
        assert isinstance(b, Arch) and b.loads == a.loads
        assert b.intrados_radii[2] == pytest.approx(ri, abs=1e-12)
        assert b.extrados_radii[2] == pytest.approx(ro, abs=1e-12)
        others = [i for i in range(7) if i != 2]
        assert np.array_equal(b.thicknesses[others], a.thicknesses[others])


def test_thickness_loss_on_a_polygon_matches_an_independently_built_arch():
    """Cross-check: the polygon path (each point moved toward the centreline along the
    intrados-extrados segment) vs a circular arch built by hand with voussoir 1 thinner, written
    as a polygon afterwards: the same k_l, k_r."""
    a = oppenheim_arch()
    for at, (dr, f) in {"centreline": (0.0, 0.7), "intrados": (0.225, 0.7),
                        "extrados": (-0.225, 0.7)}.items():
        r, t = a.radii.copy(), a.thicknesses.copy()
        r[1] += dr
        t[1] *= f
        by_hand = as_polygon(Arch(a.spans, r, t), 120)
        damaged = apply_defect(as_polygon(a, 120), Defect.thickness(1, f, at))
        assert isinstance(damaged, PolygonArch)
        assert np.allclose(damaged.areas, by_hand.areas, rtol=1e-12)
        r1, r2 = limit_analysis(damaged, verify=False), limit_analysis(by_hand, verify=False)
        assert r1.k_l == pytest.approx(r2.k_l, rel=1e-10)
        assert r1.k_r == pytest.approx(r2.k_r, rel=1e-10)


@pytest.mark.parametrize("spec", ["3:thickness=0.9999999", "0:thickness=0.9999999,at=intrados",
                                  "3:tilt=1e-7", "0:tilt=-1e-7", "7:mortar=1e-7",
                                  "3:mortar=1e-7,from=extrados"])
def test_a_vanishing_defect_gives_the_nominal_k(spec):
    res = limit_analysis(apply_defect(oppenheim_arch(), spec))
    # polygon paths approximate the sectors' arcs (<= 0.002 rad a segment)
    assert res.k_l == pytest.approx(K_OPP, abs=2e-6)
    assert res.k_r == pytest.approx(K_OPP, abs=2e-6)
    assert res.discrepancy < 1e-9  # kinematic = static on the damaged arch


def test_missing_mortar_shortens_only_the_contact():
    a = as_polygon(oppenheim_arch(), 60)
    for spec, j, end in (("3:mortar=0.25", 3, 0), ("0:mortar=0.25,from=extrados", 0, 1),
                         ("7:mortar=0.25", 7, 0)):
        b = apply_defect(a, spec)
        assert np.allclose(b.areas, a.areas, rtol=1e-13)
        assert np.allclose(b.centroids, a.centroids, atol=1e-12)
        p0, p1 = a.joint_points[j]
        q0, q1 = b.joint_points[j]
        assert np.hypot(*(q1 - q0)) == pytest.approx(0.75 * np.hypot(*(p1 - p0)), rel=1e-12)
        kept = (q0, p0) if end == 1 else (q1, p1)  # the undamaged end stays
        assert np.allclose(*kept, atol=1e-12)
        others = [k for k in range(8) if k != j]
        assert np.allclose(b.joint_points[others], a.joint_points[others], atol=1e-12)


def test_tilt_keeps_the_masonry_and_mirrors():
    a = oppenheim_arch()
    b = apply_defect(a, "3:tilt=8")
    assert b.areas.sum() == pytest.approx(a.areas.sum(), rel=1e-6)  # one cut moves, area kept
    (p0, p1) = b.joint_points[3]
    u = (p1 - p0) / np.hypot(*(p1 - p0))
    radial = np.array([np.cos(a.joint_angles[3]), np.sin(a.joint_angles[3])])
    assert np.degrees(np.arccos(u @ radial)) == pytest.approx(8.0, abs=1e-6)
    # mirror: joint j tilted by +x on the arch <-> joint n-j by -x on its mirror image
    for j in (0, 2, 3):
        r = limit_analysis(apply_defect(a, Defect.tilt(j, 6.0)), verify=False)
        m = limit_analysis(apply_defect(a.mirrored(), Defect.tilt(7 - j, -6.0)), verify=False)
        assert r.k_l == pytest.approx(m.k_r, rel=1e-9) and r.k_r == pytest.approx(m.k_l, rel=1e-9)


def test_family_arch_with_loads_keeps_its_loads():
    f = family_arch("parabolic", 10.0, 3.0, 0.6, 8, fill={"level": 3.6, "density": 1800.0})
    for spec in ("2:thickness=0.6,at=extrados", "4:tilt=-4", "5:mortar=0.3"):
        b = apply_defect(f, spec)
        assert type(b) is PolygonArch and b.loads == f.loads and b.n == f.n
        assert limit_analysis(b).discrepancy < 1e-8


# ---------------------------------------------------------------------------- defect maps
def test_oppenheim_map_30pct_thickness_loss():
    """The README's figures: voussoirs 2 and 4 (mirror images) cost the most, min(k) 0.3700 ->
    0.2616 g; the map is mirror-symmetric (voussoir i vs n-1-i swaps k_l and k_r)."""
    m = defect_map(oppenheim_arch(), "thickness", 0.7)
    assert m.worst_all == (2, 4)
    assert m.k0 == pytest.approx(K_OPP, abs=1e-12)
    assert m.k[2] == pytest.approx(0.261581, abs=1e-6)
    assert m.loss.max() == pytest.approx(0.108428, abs=1e-6)
    assert m.loss[3] == pytest.approx(0.005522, abs=1e-6)  # the crown voussoir matters least
    np.testing.assert_allclose(m.k_l, m.k_r[::-1], rtol=1e-12)
    # the same map built on the polygon form of the arch (an independent geometry path)
    mp = defect_map(as_polygon(oppenheim_arch(), 200), "thickness", 0.7)
    np.testing.assert_allclose(mp.k_l, m.k_l, rtol=2e-6)


def test_map_of_the_mirror_image_is_the_mirrored_map():
    f = family_arch("pointed", 10.0, 7.0, 0.8, 9, thickness_crown=0.6)
    d = Defect.mortar(0, 0.3)
    m, mm = defect_map(f, d), defect_map(f.mirrored(), d)
    np.testing.assert_allclose(m.k_l, mm.k_r[::-1], rtol=1e-9)
    np.testing.assert_allclose(m.k_r, mm.k_l[::-1], rtol=1e-9)


def test_map_of_an_arch_that_cannot_stand_counts_the_whole_capacity_lost():
    thin = oppenheim_arch().with_thickness_factor(0.64)  # just above the minimum thickness
    m = defect_map(thin, "thickness", 0.3, indices=[0, 3])
    assert not m.stands[0] and m.loss[0] == pytest.approx(m.k0)
    assert "cannot stand" in m.notes[0]
    assert json.loads(json.dumps(m.to_dict(), allow_nan=True))["rows"][0]["stands"] is False


# ---------------------------------------------------------------------------- command line
def test_cli_defects_json_and_plot(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    fig = tmp_path / "map.png"
    assert main(["defects", "--json", "--plot", str(fig)]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["worst"]["ties"] == [2, 4] and d["worst"]["loss"] == pytest.approx(0.108428, abs=1e-6)
    assert fig.stat().st_size > 10_000
    from archrock.reports.plots import plot_defect_map  # what the assessment report draws, no file

    drawn = plot_defect_map(defect_map(oppenheim_arch(), "mortar", 0.3))
    assert len(drawn.axes) == 2  # the map and its colour bar
    assert main(["defects", "--kind", "mortar", "--value", "0.3", "--from", "extrados"]) == 0
    assert "joint" in capsys.readouterr().out


def test_cli_defect_option(capsys):
    assert main(["limit", "--json", "--defect", "2:thickness=0.7"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["k_r"] == pytest.approx(0.261581, abs=1e-6)
    assert main(["limit", "--json", "--defect", "2:thickness=0.7", "--defect", "4:thickness=0.7"]) == 0
    d2 = json.loads(capsys.readouterr().out)
    assert d2["k_l"] == pytest.approx(d2["k_r"], rel=1e-12)  # symmetric again
    assert main(["limit", "--defect", "7:thickness=0.7"]) == 2
    assert "allowed 0..6" in capsys.readouterr().err
    assert main(["defects", "--kind", "tilt", "--at", "intrados"]) == 2


def test_every_arch_command_takes_defect(capsys):
    from archrock.cli import SUBCOMMANDS, build_parser

    parser = build_parser()
    for name in ("limit", "plot-limit", "respond", "curves", "fragility", "ensemble", "random-arch",
                 "defects"):
        assert name in SUBCOMMANDS
        args = parser.parse_args([name, "--defect", "1:thickness=0.8", "--defect", "2:tilt=3"]
                                 + (["--pulse", "oppenheim", "--amplitude", "-1",
                                     "--pulse-duration", "0.2"] if name == "respond" else [])
                                 + (["--records", "x.AT2"] if name == "fragility" else []))
        assert args.defect == ["1:thickness=0.8", "2:tilt=3"]
    assert main(["random-arch", "--seed", "1", "--defect", "1:thickness=0.8"]) == 0
    thick = [v["thickness"] for v in json.loads(capsys.readouterr().out)["voussoirs"]]
    assert thick[1] < thick[0]  # drawn around the damaged arch (1.2 m +- 10% against 1.5 m)
    assert main(["respond", "--pulse", "oppenheim", "--amplitude", "-1", "--pulse-duration", "0.2",
                 "--defect", "2:thickness=0.7", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["k_r"] == pytest.approx(0.261581, abs=1e-6) and "collapsed" in d


def test_map_with_a_pulse_reuses_collapse_amplitude():
    from archrock.studies.curves import collapse_amplitude
    from archrock.dynamics.response import prepare

    a = oppenheim_arch()
    m = defect_map(a, "thickness", 0.7, indices=[3], pulse_duration=0.2, n_scan=40)
    ref = collapse_amplitude(prepare(a), 0.2, n_scan=40)
    assert m.amplitude0 == pytest.approx(ref.amplitude, abs=1e-12)
    d = apply_defect(a, "3:thickness=0.7")
    ref3 = collapse_amplitude(prepare(d, nominal=a), 0.2, n_scan=40)
    assert m.amplitudes[0] == pytest.approx(ref3.amplitude, abs=1e-12)


def test_pulse_map_mirror_symmetry():
    """A pulse of sign -1 on the arch damaged at voussoir i collapses it at the amplitude that a
    pulse of sign +1 needs on the arch damaged at voussoir n-1-i (Oppenheim's arch is its own
    mirror image)."""
    a = oppenheim_arch()
    minus = defect_map(a, "thickness", 0.7, indices=[0, 2], pulse_duration=0.2, sign=-1, n_scan=40)
    plus = defect_map(a, "thickness", 0.7, indices=[6, 4], pulse_duration=0.2, sign=1, n_scan=40)
    np.testing.assert_allclose(minus.amplitudes, plus.amplitudes, atol=2e-3)
    assert minus.amplitude0 == pytest.approx(plus.amplitude0, abs=2e-3)
    # damage on the side the return swing (M_r) opens toward costs most: 1.29 g -> about 0.53 g
    assert minus.amplitudes[0] == pytest.approx(0.527, abs=0.01)
    assert minus.amplitude0 == pytest.approx(1.294, abs=0.01)
    both = defect_map(a, "thickness", 0.7, indices=[0, 6], pulse_duration=0.2, sign=0, n_scan=40)
    np.testing.assert_allclose(both.amplitudes, minus.amplitudes[0], atol=2e-3)  # the weaker side


@pytest.mark.slow
def test_mirror_property_on_random_arches_and_defects():
    """Any defect on an irregular arch and its mirror image on the mirrored arch swap k_l and
    k_r, and the kinematic multipliers equal the static ones (limit theorems)."""
    from hypothesis import given, settings
    from hypothesis import strategies as st

    from archrock.errors import CannotStandError
    from archrock.geometry import random_arch

    @settings(max_examples=40, deadline=None)
    @given(seed=st.integers(0, 10_000), kind=st.sampled_from(["thickness", "tilt", "mortar"]),
           index=st.integers(0, 7), value=st.floats(0.3, 0.95), side=st.booleans(),
           family=st.booleans())
    def check(seed, kind, index, value, side, family):
        nominal = family_arch("pointed", 10.0, 7.0, 1.0, 7) if family else oppenheim_arch()
        a = random_arch(nominal, seed=seed)
        n = a.n
        if kind == "thickness":
            d = Defect.thickness(min(index, n - 1), value, "intrados" if side else "centreline")
            m = Defect.thickness(n - 1 - d.index, value, d.side)
        elif kind == "tilt":
            d = Defect.tilt(index, 20 * (value - 0.6))
            m = Defect.tilt(n - index, -d.value)
        else:
            d = Defect.mortar(index, value * 0.6, "extrados" if side else "intrados")
            m = Defect.mortar(n - index, d.value, d.side)
        try:
            r = limit_analysis(apply_defect(a, d))
        except CannotStandError:
            return
        rm = limit_analysis(apply_defect(a.mirrored(), m), verify=False)
        assert r.k_l == pytest.approx(rm.k_r, rel=1e-7) and r.k_r == pytest.approx(rm.k_l, rel=1e-7)
        assert r.discrepancy < 1e-7

    check()


# ---- issue 17: a tilted springing joint adds masonry along the true circle --------------------
def _exact_tilted_springing_area(arch, degrees):
    """Area of voussoir 0 of a circular Arch whose springing joint is tilted by ``degrees``
    about its mid-point: exact arcs (Green's theorem: an arc of radius r about the origin from
    angle a to b adds r^2 (b - a) / 2, a radial joint nothing, a chord P -> Q (Px Qy - Qx Py) / 2)."""
    import math

    psi0, psi1 = arch.joint_angles[0], arch.joint_angles[1]
    r_in, r_out = arch.intrados_radii[0], arch.extrados_radii[0]
    a = r_in * np.array([math.cos(psi0), math.sin(psi0)])
    b = r_out * np.array([math.cos(psi0), math.sin(psi0)])
    m, e = 0.5 * (a + b), (b - a) / np.hypot(*(b - a))
    th = math.radians(degrees)
    u = np.array([math.cos(th) * e[0] - math.sin(th) * e[1], math.sin(th) * e[0] + math.cos(th) * e[1]])

    def hit(r, near):  # the line m + s u on the circle of radius r, nearest the old corner
        bq, cq = float(m @ u), float(m @ m) - r * r
        roots = [-bq + sg * math.sqrt(bq * bq - cq) for sg in (-1.0, 1.0)]
        pts = [m + s * u for s in roots]
        return min(pts, key=lambda p: np.hypot(*(p - near)))

    p_in, p_out = hit(r_in, a), hit(r_out, b)
    al_in, al_out = math.atan2(p_in[1], p_in[0]), math.atan2(p_out[1], p_out[0])
    area = 0.5 * r_in ** 2 * (psi1 - al_in) + 0.5 * r_out ** 2 * (al_out - psi1)
    return area + 0.5 * (p_out[0] * p_in[1] - p_in[0] * p_out[1])


@pytest.mark.parametrize("spec", ["0:tilt=5", "0:tilt=-5", "0:tilt=20", "7:tilt=5"])
def test_springing_tilt_follows_the_true_circle(spec, monkeypatch):
    """Issue 17: the masonry a tilted springing joint adds was laid along the last chord of the
    0.002 rad polyline, straight on, so k_r depended on that step (1.7e-4 between the chord
    and the circle).  Now it follows the circle.  The change of the voussoir's area agrees with
    the exact construction within 2.5e-6 m^2 (4e-7 of its 5.89 m^2; the straight chord was 6e-6
    off at 5 deg and 3.5e-4 at 20 deg), and k moves with the step no more than the undamaged
    polygon does from 0.002 to 0.0005 rad (8.7e-8; it moved 1.1e-5 along the chord)."""
    import archrock.geometry.defect as defect_module

    arch = oppenheim_arch()
    d = Defect.parse(spec)
    # the right springing of the arch is the left springing of its mirror image, tilted back
    k, deg = (-1, -d.value) if d.index == arch.n else (0, d.value)
    ref_change = _exact_tilted_springing_area(arch, deg) - arch.areas[k]
    change = apply_defect(arch, d).areas[k] - defect_module.defect_base(arch, "tilt").areas[k]
    assert abs(ref_change) > 5e-6  # the test sees the wedge
    assert change == pytest.approx(ref_change, abs=2.5e-6, rel=0)
    ks, k0 = {}, {}
    for step in (0.002, 0.0005):
        monkeypatch.setattr(defect_module, "_ARC_STEP", step)
        r = limit_analysis(apply_defect(arch, d), verify=False)
        r0 = limit_analysis(defect_module.defect_base(arch, "tilt"), verify=False)
        ks[step], k0[step] = (r.k_l, r.k_r), (r0.k_l, r0.k_r)
    for i in range(2):
        moved, moved_undamaged = abs(ks[0.002][i] - ks[0.0005][i]), abs(k0[0.002][i] - k0[0.0005][i])
        # the undamaged polygon's k moves 8.7e-8 (2.4e-7 relative: its chords' sagittas); the
        # damaged one no more (with 10% and 1e-9 of slack for rounding); the chord moved 1.1e-5
        assert 1e-8 < moved_undamaged < 1e-7
        assert moved <= 1.1 * moved_undamaged + 1e-9


def test_springing_tilt_on_a_polygon_continues_its_end_curvature():
    """A polygon arch (here a circle sampled as polylines) continues its springing lines along
    the circle through their last three vertices: the exact construction, to the sampling."""
    arch = oppenheim_arch()
    poly = as_polygon(arch, 400)
    ref_change = _exact_tilted_springing_area(arch, 20.0) - arch.areas[0]
    change = apply_defect(poly, "0:tilt=20").areas[0] - poly.areas[0]
    assert change == pytest.approx(ref_change, abs=2.5e-6, rel=0)


def test_progress_lines_go_to_the_callback_not_stderr(capsys):
    """The library prints nothing: a progress line per damaged arch goes to the callback (the
    CLI's prints it on stderr), none without one."""
    lines = []
    m = defect_map(oppenheim_arch(), "thickness", 0.7, indices=[0, 3],
                   settings=RunSettings(progress=lines.append))
    assert capsys.readouterr() == ("", "")
    assert [ln.split("  [")[0] for ln in lines] == [
        f"  voussoir {i} ({j + 1}/2): k_l = {m.k_l[j]:.4f}, k_r = {m.k_r[j]:.4f}"
        for j, i in enumerate((0, 3))]
    defect_map(oppenheim_arch(), "thickness", 0.7, indices=[0])
    assert capsys.readouterr() == ("", "")
    # the one protocol (archrock._progress): anything but None, True or a callable is refused
    with pytest.raises(ArchInputError, match=r"^progress: 'yes'; allowed None, True"):
        defect_map(oppenheim_arch(), settings={"progress": "yes"})
    with pytest.raises(TypeError, match="unexpected keyword argument 'progress'"):
        defect_map(oppenheim_arch(), progress=lines.append)  # 0.6's keyword, gone in 0.7


def test_side_is_one_spelling_with_the_old_ones_read(capsys):
    """side= / --side for both kinds that have a side; at= (thickness) and from= (mortar), the
    0.5 spellings, still read; spec() writes side=."""
    from archrock.cli import main

    d = Defect.parse("2:thickness=0.6,at=extrados")
    assert d == Defect.parse("2:thickness=0.6,side=extrados")
    assert d.spec() == "2:thickness=0.6,side=extrados" and Defect.parse(d.spec()) == d
    assert main(["defects", "--kind", "thickness", "--side", "extrados", "--at", "intrados"]) == 2
    assert "--side: given more than once" in capsys.readouterr().err
    assert main(["defects", "--kind", "tilt", "--side", "intrados"]) == 2
    assert "a tilted joint has no side" in capsys.readouterr().err
