"""Every bad input at the door gives one line (issue 29): oversized or endless files, numbers
past double precision or past any real structure, a load the arch cannot carry."""

import json
import os

import pytest

from archrock.cli import main
from archrock.geometry import nominal_arch
from archrock.geometry.arcade import arcade

VOUSSOIRS = [{"span_deg": 22.5, "radius": 10.0, "thickness": 1.5}] * 7


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def one_line(capsys, code, *argv) -> str:
    got, _, err = run(capsys, *argv)
    assert got == code and err.count("\n") == 1, err
    return err.rstrip("\n")


def _json(tmp_path, name, data):
    p = tmp_path / name
    p.write_text(json.dumps(data), encoding="utf-8")
    return p


def test_a_401_digit_radius(capsys, tmp_path):
    p = _json(tmp_path, "big.json", {"voussoirs": [{**VOUSSOIRS[0], "radius": int("1" * 401)}]
                                     + VOUSSOIRS[1:]})
    assert one_line(capsys, 2, "limit", "--geometry", p) == (
        f"archrock: error: {p}: voussoirs[0].radius: a 401-digit number is out of range; "
        f"allowed 1e-08 m to 1e+08 m")


def test_arcade_coordinates_of_1e200(capsys, tmp_path):
    doc = arcade([nominal_arch(), nominal_arch()], 3.0, 4.0).to_dict()
    for b in doc["blocks"]:
        b["outline"] = [[x * 1e200, y * 1e200] for x, y in b["outline"]]
    p = _json(tmp_path, "a200.json", doc)
    line = one_line(capsys, 2, "arcade", "--arcade", p, "--json")
    assert line.startswith(f"archrock: error: {p}: blocks[0].outline: coordinate ")
    assert line.endswith("e+200 m is out of range; allowed |x|, |y| <= 1e+09 m (units? lengths "
                         "are in metres)")


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_endless_geometry_files(capsys, device):
    assert one_line(capsys, 2, "limit", "--geometry", device) == (
        f"archrock: error: {device}: geometry file too large (more than 10000000 bytes, read "
        f"from a stream); allowed at most 10 MB (10000000 bytes)")


def test_a_geometry_file_past_10_mb(capsys, tmp_path):
    p = tmp_path / "huge.json"
    with open(p, "wb") as f:
        f.truncate(11_000_000)
    assert one_line(capsys, 2, "limit", "--geometry", p) == (
        f"archrock: error: {p}: geometry file too large (11000000 bytes); allowed at most 10 MB "
        f"(10000000 bytes)")


@pytest.mark.skipif(not os.path.exists("/dev/urandom"), reason="needs /dev/urandom")
def test_an_endless_record(capsys, tmp_path, monkeypatch):
    from archrock.geometry.inputfile import MAX_INPUT_BYTES

    monkeypatch.setitem(MAX_INPUT_BYTES, "record", 1000)  # the same path, read faster
    assert one_line(capsys, 2, "respond", "--record", "/dev/urandom") == (
        "archrock: error: record path: /dev/urandom: record file too large (more than 1000 "
        "bytes, read from a stream); allowed at most 0.001 MB (1000 bytes)")


def test_a_load_the_arch_cannot_carry(capsys, tmp_path):
    p = _json(tmp_path, "heavy.json", {"voussoirs": VOUSSOIRS,
                                       "loads": [{"voussoir": 3, "mass": 1e12, "at": [0, 11]}]})
    line = one_line(capsys, 3, "limit", "--geometry", p)
    assert line.startswith("archrock: outcome: arch: load 0 (1e+12 kg/m on voussoir 3 at (0, 11) "
                           "m) is more than it can carry (k_l = ")
    assert line.endswith("it stands without its loads; it carries at most 3.09e+05 kg/m there "
                         "(load 0 alone): reduce load 0's mass or thicken the arch")


def test_a_load_past_1e12_kg(capsys, tmp_path):
    p = _json(tmp_path, "l.json", {"voussoirs": VOUSSOIRS,
                                   "loads": [{"voussoir": 3, "mass": 1e13, "at": [0, 11]}]})
    assert one_line(capsys, 2, "limit", "--geometry", p) == (
        f"archrock: error: {p}: loads[0].mass: 1e+13 is out of range; allowed 0 to 1e+12 kg per "
        f"metre of depth")


@pytest.mark.parametrize("argv, line", [
    (("limit", "--pier-width", "2", "--pier-height", "1e-300"),
     "archrock: error: --pier-height: 1e-300 m is out of range; allowed 2.109e-05 m (a millionth "
     "of the arch's extent) to 2109 m (100 times it)"),
    (("limit", "--defect", "2:mortar=1e-300"),
     "archrock: error: defect mortar: 1e-300 is out of range; allowed a fraction of the joint's "
     "contact length, 0 < value < 1 (at least 1e-09)"),
    (("limit", "--density", "1e300"),
     "archrock: error: density: 1e+300 is out of range; allowed 1e-08 to 1e+08 kg/m^3"),
    (("respond", "--pulse", "oppenheim", "--amplitude", "-0.5", "--pulse-duration", "1e-300"),
     "archrock: error: pulse duration: 1e-300 s is out of range; allowed 1e-06 s to 10000 s"),
    (("arcade", "--spans", "4", "--pier-height", "1e-300", "--pier-width", "1"),
     "archrock: error: --pier-height: value 1 (pier 1): 1e-300 m is out of range; allowed "
     "4.4e-06 m (a millionth of the largest arch's extent) to 440 m (100 times it)"),
])
def test_flags_bounded(capsys, argv, line):
    assert one_line(capsys, 2, *argv) == line


def test_normal_inputs_still_work(capsys, tmp_path):
    code, out, _ = run(capsys, "limit", "--json")
    assert code == 0 and abs(json.loads(out)["k"] - 0.3700) < 1e-3  # Oppenheim's arch
    code, out, _ = run(capsys, "limit", "--shape", "pointed", "--span", "10", "--rise", "6",
                       "--thickness", "0.8", "--json")
    assert code == 0 and json.loads(out)["k"] > 0
    p = tmp_path / "a.json"
    code, _, _ = run(capsys, "arcade", "--spans", "4", "5", "--pier-height", "3",
                     "--pier-width", "1", "--write", p)
    assert code == 0
    code, out, _ = run(capsys, "arcade", "--arcade", p, "--json")
    assert code == 0 and json.loads(out)["arcade"]["blocks"] == 21
