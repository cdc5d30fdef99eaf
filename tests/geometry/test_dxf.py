"""Surveyed arches from DXF drawings (archrock.geometry.dxf, archrock import-dxf): round trips of a
circular and a pointed arch, units, and the one-line refusals."""

import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.geometry.dxf import arch_from_outlines, read_dxf
from archrock.errors import ArchInputError
from archrock.geometry.files import read_arch
from archrock.geometry import as_polygon, family_arch, oppenheim_arch
from archrock.statics.limit import limit_analysis

ezdxf = pytest.importorskip("ezdxf")


def _write_dxf(path, outlines, *, scale=1.0, seed=0, layer="VOUSSOIRS", lw=True):
    """One closed polyline per outline, in shuffled order, each from a random vertex in a
    random direction; unrelated lines in between make the handles irregular."""
    rng = np.random.default_rng(seed)
    doc = ezdxf.new()
    msp = doc.modelspace()
    handles = {}
    for i in rng.permutation(len(outlines)):
        o = np.asarray(outlines[i], float) * scale
        o = np.roll(o, int(rng.integers(len(o))), axis=0)
        if rng.random() < 0.5:
            o = o[::-1]
        for _ in range(int(rng.integers(0, 4))):
            msp.add_line((0, 0), (1, 1), dxfattribs={"layer": "construction"})
        if lw:
            e = msp.add_lwpolyline(o.tolist(), close=True, dxfattribs={"layer": layer})
        else:
            e = msp.add_polyline2d(o.tolist(), close=True, dxfattribs={"layer": layer})
        handles[int(i)] = e.dxf.handle
    doc.saveas(path)
    return handles


def _same(a, b):
    np.testing.assert_allclose(b.joint_points, a.joint_points, rtol=0, atol=1e-9)
    np.testing.assert_allclose(b.masses, a.masses, rtol=1e-12)
    ra, rb = limit_analysis(a), limit_analysis(b)
    assert rb.k_l == pytest.approx(ra.k_l, abs=1e-9)
    assert rb.k_r == pytest.approx(ra.k_r, abs=1e-9)
    assert rb.mechanism_l.label == ra.mechanism_l.label


def _outlines(arch):
    return [arch.outline(i) for i in range(arch.n)]


@pytest.mark.parametrize("seed", [0, 1])
def test_oppenheim_round_trip(tmp_path, seed):
    arch = as_polygon(oppenheim_arch(), 20)
    handles = _write_dxf(tmp_path / "opp.dxf", _outlines(arch), seed=seed)
    back, order = read_dxf(tmp_path / "opp.dxf", layer="voussoirs")
    assert order == tuple(handles[i] for i in range(arch.n))
    assert back.name == "opp"
    _same(arch, back)


def test_pointed_family_arch_round_trip_with_polyline2d(tmp_path):
    arch = family_arch("pointed", 10.0, 7.0, 1.0, 13)  # a keystone with a vertex on x = 0
    _write_dxf(tmp_path / "p.dxf", _outlines(arch), seed=3, lw=False)
    back, _ = read_dxf(tmp_path / "p.dxf")
    _same(arch, back)


def test_vertical_joints_and_varying_thickness(tmp_path):
    arch = family_arch("elliptical", 10.0, 3.0, 0.8, 9, thickness_crown=0.5, joints="vertical")
    _write_dxf(tmp_path / "e.dxf", _outlines(arch), seed=4)
    _same(arch, read_dxf(tmp_path / "e.dxf")[0])


def test_millimetres(tmp_path):
    arch = as_polygon(oppenheim_arch(), 20)
    _write_dxf(tmp_path / "mm.dxf", _outlines(arch), scale=1000.0, seed=5)
    back, _ = read_dxf(tmp_path / "mm.dxf", units="mm")
    _same(arch, back)


def test_cli_writes_the_geometry_file(tmp_path, capsys):
    arch = as_polygon(oppenheim_arch(), 20)
    handles = _write_dxf(tmp_path / "d.dxf", _outlines(arch), scale=100.0, seed=6)
    out = tmp_path / "sub" / "arch.json"
    code = main(["import-dxf", str(tmp_path / "d.dxf"), "--layer", "VOUSSOIRS", "--units", "cm",
                 "--density", "2400", "--out", str(out)])
    assert code == 0
    back = read_arch(out)
    assert back.density == 2400.0
    np.testing.assert_allclose(back.joint_points, arch.joint_points, rtol=0, atol=1e-9)
    meta = json.loads(out.read_text())["metadata"]
    assert meta["handles"] == [handles[i] for i in range(arch.n)] and meta["units"] == "cm"
    assert "wrote" in capsys.readouterr().err


def test_overhanging_faces_and_collinear_vertices():
    """Neighbours of different thickness (faces on one line, one longer), and a face drawn as
    two collinear edges."""
    outlines = [
        [(0, 0), (1, 0), (1, 1.2), (0, 1.2)],
        [(1, 0), (2, 0), (2, 1), (1, 1), (1, 0.5)],
        [(2, 0), (3, 0), (3, 1), (2, 1)],
    ]
    arch, order = arch_from_outlines(outlines)
    assert order == (0, 1, 2)
    np.testing.assert_allclose(arch.joint_points[1], [[1, 0], [1, 1]])
    np.testing.assert_allclose(arch.joint_points[0], [[0, 0], [0, 1.2]])
    np.testing.assert_allclose(arch.intrados[1], [[1, 0], [2, 0]])  # below: the flat arch's intrados


# ---------------------------------------------------------------------------- refusals
def _error(tmp_path, outlines, **kw):
    _write_dxf(tmp_path / "bad.dxf", outlines, seed=kw.pop("seed", 0))
    with pytest.raises(ArchInputError) as exc:
        read_dxf(tmp_path / "bad.dxf", **kw)
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


def test_gap_names_both_voussoirs_and_the_gap(tmp_path):
    arch = as_polygon(oppenheim_arch(), 20)
    outlines = _outlines(arch)
    outlines[3] = outlines[3] + np.array([0.0, 0.05])  # the keystone lifted by 5 cm
    handles = _write_dxf(tmp_path / "gap.dxf", outlines, seed=7)
    with pytest.raises(ArchInputError, match="do not touch: a gap of 0.0") as exc:
        read_dxf(tmp_path / "gap.dxf")
    msg = str(exc.value)
    assert {handles[2], handles[3]} <= set(msg.replace(",", " ").split()) or \
        {handles[3], handles[4]} <= set(msg.replace(",", " ").split())


def test_missing_layer_lists_the_layers_with_polylines(tmp_path):
    msg = _error(tmp_path, _outlines(as_polygon(oppenheim_arch(), 5)), layer="arches")
    assert "layer 'arches' has no closed polylines" in msg and "'VOUSSOIRS'" in msg


def test_polyline_with_two_vertices(tmp_path):
    outlines = _outlines(as_polygon(oppenheim_arch(), 5)) + [[(50, 50), (51, 50)]]
    assert "2 distinct vertices" in _error(tmp_path, outlines)


def test_voussoir_touching_three_others():
    outlines = [[(0, 0), (1, 0), (1, 1), (0, 1)], [(1, 0), (2, 0), (2, 1), (1, 1)],
                [(2, 0), (3, 0), (3, 1), (2, 1)], [(1, 1), (2, 1), (2, 2), (1, 2)]]
    with pytest.raises(ArchInputError, match="voussoir 1 touches 3 others"):
        arch_from_outlines(outlines)


@pytest.mark.parametrize("left", [[(0.8, 0), (0.8, 1)], [(0.9, 0), (1.1, 1)]])
def test_overlapping_neighbours(left):
    (x0, y0), (x1, y1) = left
    outlines = [[(0, 0), (1, 0), (1, 1), (0, 1)], [(x0, y0), (2, 0), (2, 1), (x1, y1)],
                [(2, 0), (3, 0), (3, 1), (2, 1)]]
    with pytest.raises(ArchInputError, match=r"voussoirs 0 and 1 overlap by 0\.[0-9]+ m"):
        arch_from_outlines(outlines)


def test_overlap_within_the_tolerance_is_a_contact():
    outlines = [[(0, 0), (1, 0), (1, 1), (0, 1)], [(1 - 1e-4, 0), (2, 0), (2, 1), (1 - 1e-4, 1)],
                [(2, 0), (3, 0), (3, 1), (2, 1)]]
    arch, _ = arch_from_outlines(outlines)
    assert arch.n == 3


def test_ring_and_too_few():
    with pytest.raises(ArchInputError, match="at least 3 voussoirs"):
        arch_from_outlines([[(0, 0), (1, 0), (1, 1)], [(1, 0), (2, 0), (1, 1)]])
    ring = [[(0, 0), (1, 0), (1, 1), (0, 1)], [(1, 0), (2, 0), (2, 1), (1, 1)],
            [(1, 1), (2, 1), (2, 2), (1, 2)], [(0, 1), (1, 1), (1, 2), (0, 2)]]
    with pytest.raises(ArchInputError, match="ring"):
        arch_from_outlines(ring)


def test_cli_refusal_is_one_line(tmp_path, capsys):
    _write_dxf(tmp_path / "d.dxf", _outlines(as_polygon(oppenheim_arch(), 5)))
    code = main(["import-dxf", str(tmp_path / "d.dxf"), "--layer", "nope"])
    err = capsys.readouterr().err
    assert code == 2 and err.startswith("archrock: error: ") and err.count("\n") == 1
    assert main(["import-dxf", str(tmp_path / "missing.dxf")]) == 2
    assert "DXF file not found" in capsys.readouterr().err


def test_drawing_in_millimetres_read_as_metres_is_refused_with_the_units_hint(tmp_path, capsys):
    """Issue 17: a DXF drawn in millimetres read as a 21 km arch; now refused naming the size,
    the allowed range and --units mm (with the size it gives), and the header's units."""
    arch = as_polygon(oppenheim_arch(), 5)
    _write_dxf(tmp_path / "mm.dxf", _outlines(arch), scale=1000.0, seed=5)
    code = main(["import-dxf", str(tmp_path / "mm.dxf")])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert err.startswith("archrock: error: ")
    assert "mm.dxf: the arch is 2.109e+04 m across read in m; allowed 0.01 m to 500 m " \
           "(units? drawn in mm? give --units mm (21.09 m))" in err
    # a drawing whose header says millimetres: the message says so too
    doc = ezdxf.readfile(tmp_path / "mm.dxf")
    doc.header["$INSUNITS"] = 4
    doc.saveas(tmp_path / "mm.dxf")
    with pytest.raises(ArchInputError, match=r"give --units mm \(21\.09 m\); the DXF header says mm"):
        read_dxf(tmp_path / "mm.dxf")
    # a drawing in metres read as millimetres: 2 cm, refused the other way
    from archrock.geometry import nominal_arch

    _write_dxf(tmp_path / "m.dxf", _outlines(as_polygon(nominal_arch(0.05, 157.5, 0.01, 7), 5)))
    with pytest.raises(ArchInputError, match=r"the arch is 0\.0001079 m across read in mm; allowed "
                                             r"0\.01 m to 500 m \(units\? drawn in m\? give --units m "
                                             r"\(0\.1079 m\); the DXF header says m\)"):
        read_dxf(tmp_path / "m.dxf", units="mm")
    assert read_dxf(tmp_path / "mm.dxf", units="mm")[0].n == 7
