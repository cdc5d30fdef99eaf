"""JSON geometry files: round trip, the documented format, and one-line errors naming file and field."""

import json
import math

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry.files import read_arch, write_arch
from archrock.geometry import oppenheim_arch, random_arch


def _voussoirs(n=3, span=30.0, radius=10.0, thickness=1.0):
    return [{"span_deg": span, "radius": radius, "thickness": thickness} for _ in range(n)]


def _write(tmp_path, name, content):
    p = tmp_path / name
    p.write_text(content if isinstance(content, str) else json.dumps(content))
    return p


def test_documented_format_is_read_in_degrees_from_the_left(tmp_path):
    data = {"voussoirs": [{"span_deg": 20.0, "radius": 10.0, "thickness": 1.5},
                          {"span_deg": 40.0, "radius": 10.2, "thickness": 1.4},
                          {"span_deg": 30.0, "radius": 9.9, "thickness": 1.6}],
            "density": 2400}
    arch = read_arch(_write(tmp_path, "three.json", data))
    np.testing.assert_allclose(np.degrees(arch.spans), [20.0, 40.0, 30.0], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(arch.radii, [10.0, 10.2, 9.9])
    np.testing.assert_array_equal(arch.thicknesses, [1.5, 1.4, 1.6])
    assert arch.density == 2400.0
    assert arch.name == "three"
    # voussoir 0 is at the left springing: joint 0 at polar angle 90 + 90/2 = 135 deg
    assert math.degrees(arch.joint_angles[0]) == pytest.approx(135.0, abs=1e-12)


def test_density_is_optional(tmp_path):
    arch = read_arch(_write(tmp_path, "a.json", {"voussoirs": _voussoirs()}))
    assert arch.density == 2000.0


def test_round_trip_is_exact_and_metadata_is_ignored(tmp_path):
    a = random_arch(seed=11)
    p = write_arch(a, tmp_path / "r.json", metadata={"seed": 11})
    raw = json.loads(p.read_text())
    assert raw["metadata"] == {"seed": 11}
    assert len(raw["voussoirs"]) == 7
    b = read_arch(p)
    np.testing.assert_array_equal(b.radii, a.radii)
    np.testing.assert_array_equal(b.thicknesses, a.thicknesses)
    np.testing.assert_allclose(b.spans, a.spans, rtol=0, atol=1e-15)
    assert b.density == a.density


def test_oppenheim_file_matches_the_nominal_arch(tmp_path):
    p = write_arch(oppenheim_arch(), tmp_path / "opp.json")
    raw = json.loads(p.read_text())
    assert [v["span_deg"] for v in raw["voussoirs"]] == pytest.approx([22.5] * 7, abs=1e-12)
    assert raw["density"] == 2000.0


@pytest.mark.parametrize("name, content, fragments", [
    ("badjson.json", '{"voussoirs": [\n  {"span_deg": 30,\n}', ["line 3, column 1", "invalid JSON"]),
    ("list.json", [1, 2, 3], ["geometry", "object"]),
    ("empty.json", {"voussoirs": []}, ["voussoirs", "empty"]),
    ("missing.json", {"voussoirs": [{"span_deg": 30, "radius": 10}] * 3}, ["voussoirs[0].thickness", "missing"]),
    ("text.json", {"voussoirs": [{"span_deg": "30", "radius": 10, "thickness": 1}] * 3},
     ["voussoirs[0].span_deg", "number"]),
    ("nan.json", '{"voussoirs": [{"span_deg": 30, "radius": NaN, "thickness": 1}]}',
     ["voussoirs[0].radius", "finite"]),
    ("two.json", {"voussoirs": _voussoirs(n=2)}, ["voussoirs", "at least 3"]),
    ("full.json", {"voussoirs": _voussoirs(n=3, span=120.0)}, ["spans", "360"]),
    ("negt.json", {"voussoirs": _voussoirs(thickness=-1.0)}, ["thickness of voussoir 0", "0 < t < 2 R"]),
    ("gap.json", {"voussoirs": _voussoirs(n=2) + _voussoirs(n=1, radius=12.0) + _voussoirs(n=2)},
     ["joint 2", "overlap"]),
    ("dens.json", {"voussoirs": _voussoirs(), "density": -5}, ["density", "> 0"]),
])
def test_bad_files_give_one_line_naming_file_and_field(tmp_path, name, content, fragments):
    p = _write(tmp_path, name, content)
    with pytest.raises(ArchInputError) as info:
        read_arch(p)
    msg = str(info.value)
    assert "\n" not in msg
    assert name in msg
    for f in fragments:
        assert f in msg


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(ArchInputError, match=r"nothere\.json: geometry file not found"):
        read_arch(tmp_path / "nothere.json")
    with pytest.raises(ArchInputError, match="is a directory"):
        read_arch(tmp_path)


def test_binary_file_is_refused(tmp_path):
    p = tmp_path / "bin.json"
    p.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(ArchInputError, match=r"bin\.json: not a text file"):
        read_arch(p)


def test_write_to_missing_folder_names_the_file(tmp_path):
    target = tmp_path / "no" / "such" / "dir" / "a.json"
    with pytest.raises(ArchInputError, match=r"a\.json: cannot write"):
        write_arch(oppenheim_arch(), target)


# ---------------------------------------------------------------------------- polygon format, loads
def test_polygon_format_round_trip_with_loads(tmp_path):
    from archrock.geometry import PolygonArch, family_arch

    a = family_arch("pointed", 12.0, 8.0, 0.9, 7, loads=[{"voussoir": 5, "mass": 8000.0,
                                                         "at": [4.0, 7.0]}],
                    fill={"level": 9.0, "density": 1800.0}, name="p")
    p = write_arch(a, tmp_path / "pointed.json", metadata={"shape": "pointed"})
    raw = json.loads(p.read_text())
    assert set(raw["voussoirs"][0]) == {"intrados", "extrados"}
    assert raw["loads"][0] == {"voussoir": 5, "mass": 8000.0, "at": [4.0, 7.0]}
    b = read_arch(p)
    assert isinstance(b, PolygonArch) and b.name == "pointed"
    np.testing.assert_array_equal(b.joint_points, a.joint_points)
    np.testing.assert_array_equal(b.masses, a.masses)
    np.testing.assert_array_equal(b.centroids, a.centroids)
    assert b.loads == a.loads


def test_documented_polygon_format(tmp_path):
    data = {"voussoirs": [{"intrados": [[-5, 0], [-4, 3]], "extrados": [[-6, 0], [-5, 4]]},
                          {"intrados": [[-4, 3], [4, 3]], "extrados": [[-5, 4], [5, 4]]},
                          {"intrados": [[4, 3], [5, 0]], "extrados": [[5, 4], [6, 0]]}],
            "density": 2000, "loads": [{"voussoir": 1, "mass": 8000.0, "at": [0.0, 5.0]}]}
    arch = read_arch(_write(tmp_path, "box.json", data))
    assert arch.n == 3 and arch.masses[1] == pytest.approx(2000 * 9 + 8000)  # a 1 m trapezoid, 8 to 10 m
    np.testing.assert_array_equal(arch.joint_points[1], [[-4, 3], [-5, 4]])


def test_loads_in_the_circular_format_round_trip(tmp_path):
    from archrock.geometry import Arch, Load

    a = oppenheim_arch()
    a = Arch(a.spans, a.radii, a.thicknesses, a.density, "loaded", (Load(3, 5000.0, (0.0, 11.5)),))
    b = read_arch(write_arch(a, tmp_path / "l.json"))
    assert isinstance(b, Arch) and b.loads == a.loads
    np.testing.assert_array_equal(b.masses, a.masses)


def test_bad_polygon_file_names_file_and_field(tmp_path):
    data = {"voussoirs": [{"intrados": [[0, 0]], "extrados": [[0, 1], [1, 1]]}] * 3}
    with pytest.raises(ArchInputError, match=r"bad\.json: voussoirs\[0\]\.intrados"):
        read_arch(_write(tmp_path, "bad.json", data))
    with pytest.raises(ArchInputError, match="mixes"):
        read_arch(_write(tmp_path, "mix.json", {"voussoirs": [
            {"intrados": [[0, 0], [1, 0]], "extrados": [[0, 1], [1, 1]]},
            {"span_deg": 10, "radius": 1, "thickness": 0.1}]}))
