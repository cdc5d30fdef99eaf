"""Input files bounded by size at the door (geometry.inputfile), and the numbers in them
bounded by magnitude before any arithmetic (geometry files, arcade documents, loads)."""

import json
import os

import pytest

from archrock.errors import ArchInputError
from archrock.geometry import inputfile, nominal_arch
from archrock.geometry.files import read_arcade, read_arch, write_arch
from archrock.geometry.inputfile import MAX_INPUT_BYTES, read_input

OPPENHEIM_VOUSSOIRS = [{"span_deg": 22.5, "radius": 10.0, "thickness": 1.5}] * 7


def _json(tmp_path, name, data):
    p = tmp_path / name
    p.write_text(json.dumps(data), encoding="utf-8")
    return p


def test_each_kind_has_a_stated_limit():
    assert MAX_INPUT_BYTES == {"geometry": 10_000_000, "arcade": 10_000_000,
                               "record": 50_000_000, "DXF": 50_000_000, "spectrum": 1_000_000}
    with pytest.raises(ArchInputError, match="input kind: 'image'; allowed geometry, arcade"):
        read_input(__file__, "image")


def test_a_regular_file_past_the_limit_is_refused_before_reading(tmp_path):
    p = tmp_path / "big.json"
    with open(p, "wb") as f:
        f.truncate(MAX_INPUT_BYTES["geometry"] + 1)  # sparse: nothing to read, only stat
    with pytest.raises(ArchInputError) as exc:
        read_arch(p)
    assert str(exc.value) == (f"{p}: geometry file too large (10000001 bytes); allowed at most "
                              f"10 MB (10000000 bytes)")


def test_a_file_at_the_limit_is_read(tmp_path, monkeypatch):
    monkeypatch.setitem(MAX_INPUT_BYTES, "geometry", 50)
    p = tmp_path / "a.txt"
    p.write_bytes(b"x" * 50)
    assert read_input(p, "geometry") == b"x" * 50
    p.write_bytes(b"x" * 51)
    with pytest.raises(ArchInputError, match=r"geometry file too large \(51 bytes\); allowed "
                                             r"at most 5e-05 MB \(50 bytes\)"):
        read_input(p, "geometry")


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_a_stream_is_read_up_to_the_limit_only(device, monkeypatch):
    """A device reports size 0: it is read up to limit + 1 bytes (it ran out of memory, or
    forever, before)."""
    monkeypatch.setitem(MAX_INPUT_BYTES, "geometry", 1000)
    with pytest.raises(ArchInputError) as exc:
        read_arch(device)
    assert str(exc.value) == (f"{device}: geometry file too large (more than 1000 bytes, read "
                              f"from a stream); allowed at most 0.001 MB (1000 bytes)")


def test_missing_and_directory_name_the_kind(tmp_path):
    with pytest.raises(ArchInputError, match=r"nope\.json: arcade file not found"):
        read_arcade(tmp_path / "nope.json")
    with pytest.raises(ArchInputError, match="is a directory, expected a DXF file"):
        read_input(tmp_path, "DXF")


def test_every_reader_goes_through_the_bounded_one(tmp_path, monkeypatch):
    """Records (two-column and PEER), their checksums, DXF drawings and spectra are bounded
    by their kind's limit."""
    from archrock.groundmotion import RecordSpec
    from archrock.groundmotion.records import load_record
    from archrock.studies.codecheck import SiteSpectrum

    for kind in MAX_INPUT_BYTES:
        monkeypatch.setitem(MAX_INPUT_BYTES, kind, 10)
    p = tmp_path / "r.txt"
    p.write_text("0 0.1\n0.01 0.2\n0.02 0.0\n", encoding="utf-8")
    with pytest.raises(ArchInputError, match=r"record .*r\.txt: record file too large"):
        load_record(p)
    with pytest.raises(ArchInputError, match=r"record path: .*r\.txt: record file too large"):
        RecordSpec.from_file(p)
    with pytest.raises(ArchInputError, match=r"r\.txt: spectrum file too large"):
        SiteSpectrum.from_file(p)
    pytest.importorskip("ezdxf")
    from archrock.geometry.dxf import read_dxf

    d = tmp_path / "d.dxf"
    d.write_text("0\nSECTION\n2\nENTITIES\n0\nENDSEC\n0\nEOF\n", encoding="utf-8")
    with pytest.raises(ArchInputError, match=r"d\.dxf: DXF file too large \([0-9]+ bytes\)"):
        read_dxf(d)


def test_normal_files_still_read(tmp_path):
    a = nominal_arch()
    back = read_arch(write_arch(a, tmp_path / "opp.json"))
    assert back.n == 7 and abs(float(back.radii[0]) - 10.0) < 1e-12
    assert inputfile.read_input(tmp_path / "opp.json", "geometry").startswith(b"{")


# -- numbers bounded before any arithmetic --------------------------------------------------

@pytest.mark.parametrize("field, value, message", [
    ("radius", int("1" * 401), "voussoirs[0].radius: a 401-digit number is out of range; "
                               "allowed 1e-08 m to 1e+08 m"),
    ("radius", 1e9, "voussoirs[0].radius: 1e+09 m is out of range; allowed 1e-08 m to 1e+08 m"),
    ("thickness", 1e-9, "voussoirs[0].thickness: 1e-09 m is out of range; allowed 1e-08 m to "
                        "1e+08 m"),
    ("span_deg", 10 ** 400, "voussoirs[0].span_deg: a 401-digit number is out of range; allowed "
                            "0 < span_deg < 360"),
])
def test_a_voussoir_field_out_of_range_names_it(tmp_path, field, value, message):
    vs = [dict(v) for v in OPPENHEIM_VOUSSOIRS]
    vs[0][field] = value
    with pytest.raises(ArchInputError) as exc:
        read_arch(_json(tmp_path, "g.json", {"voussoirs": vs}))
    assert str(exc.value).startswith(f"{tmp_path / 'g.json'}: {message}")


def test_a_number_of_5000_digits_is_one_line(tmp_path):
    p = tmp_path / "d.json"
    p.write_text('{"voussoirs": ' + "9" * 5000 + "}", encoding="utf-8")
    with pytest.raises(ArchInputError, match="a number of more than 4300 digits"):
        read_arch(p)


@pytest.mark.parametrize("load, message", [
    ({"voussoir": 3, "mass": 10 ** 400, "at": [0, 11]},
     "loads[0].mass: a 401-digit number is out of range; allowed 0 to 1e+12 kg per metre of depth"),
    ({"voussoir": 3, "mass": 2e12, "at": [0, 11]},
     "loads[0].mass: 2e+12 is out of range; allowed 0 to 1e+12 kg per metre of depth"),
    ({"voussoir": 3, "mass": 8000, "at": [1e200, 11]},
     "loads[0].at: coordinate 1e+200 m is out of range; allowed |x|, |y| <= 1e+09 m"),
    ({"voussoir": 3, "mass": 8000, "at": [10 ** 400, 11]},
     "loads[0].at: a coordinate too large for double precision; allowed |x|, |y| <= 1e+09 m"),
])
def test_a_load_out_of_range_names_its_field(tmp_path, load, message):
    with pytest.raises(ArchInputError) as exc:
        read_arch(_json(tmp_path, "l.json", {"voussoirs": OPPENHEIM_VOUSSOIRS, "loads": [load]}))
    assert message in str(exc.value)


@pytest.mark.parametrize("density, message", [
    (1e300, "density: 1e+300 is out of range; allowed 1e-08 to 1e+08 kg/m^3"),
    (10 ** 400, "density: a 401-digit number is out of range; allowed > 0 kg/m^3"),
])
def test_density_bounded(tmp_path, density, message):
    with pytest.raises(ArchInputError) as exc:
        read_arch(_json(tmp_path, "d.json", {"voussoirs": OPPENHEIM_VOUSSOIRS,
                                             "density": density}))
    assert message in str(exc.value)


def test_polygon_points_bounded(tmp_path):
    from archrock.geometry import as_polygon

    data = as_polygon(nominal_arch(), 4).to_dict()
    data["voussoirs"][2]["extrados"][1][0] = 1e200
    with pytest.raises(ArchInputError, match=r"voussoirs\[2\]\.extrados: coordinate 1e\+200 m "
                                             r"is out of range; allowed \|x\|, \|y\| <= 1e\+09 m"):
        read_arch(_json(tmp_path, "p.json", data))
    data["voussoirs"][2]["extrados"][1][0] = 10 ** 400
    with pytest.raises(ArchInputError, match="a coordinate too large for double precision"):
        read_arch(_json(tmp_path, "p.json", data))


def test_arcade_coordinates_and_loads_bounded(tmp_path):
    from archrock.geometry.arcade import arcade

    doc = arcade([nominal_arch(), nominal_arch()], 3.0, 4.0).to_dict()
    assert read_arcade(_json(tmp_path, "ok.json", doc)).blocks  # the document as written reads
    big = json.loads(json.dumps(doc))
    for b in big["blocks"]:
        b["outline"] = [[x * 1e200, y * 1e200] for x, y in b["outline"]]
    with pytest.raises(ArchInputError, match=r"blocks\[0\]\.outline: coordinate -?[0-9.]+e\+200 "
                                             r"m is out of range; allowed \|x\|, \|y\| <= 1e\+09"):
        read_arcade(_json(tmp_path, "big.json", big))
    heavy = json.loads(json.dumps(doc))
    heavy["blocks"][3]["loads"] = [{"mass": 10 ** 400, "at": [0.0, 11.0]}]
    with pytest.raises(ArchInputError, match=r"blocks\[3\]\.loads\[0\]\.mass: a 401-digit number "
                                             r"is out of range; allowed 0 to 1e\+12 kg"):
        read_arcade(_json(tmp_path, "heavy.json", heavy))


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs named pipes")
def test_a_named_pipe_without_writer_does_not_hang(tmp_path):
    fifo = tmp_path / "pipe.json"
    os.mkfifo(fifo)
    assert read_input(fifo, "geometry") == b""  # opened without blocking: no writer, no bytes
    with pytest.raises(ArchInputError, match=r"pipe\.json: invalid JSON at line 1, column 1"):
        read_arch(fifo)
