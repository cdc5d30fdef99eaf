"""Record suites: a folder of PEER .AT2 files read once, with the sha256 of each file, and
fragility on a folder equal to fragility on its files."""

import hashlib
import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.errors import ArchInputError
from archrock.groundmotion import G
from archrock.groundmotion.suite import read_records, read_suite


def write_at2(path, accel_g, dt=0.01, title="Synthetic"):
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", f"{title}, 1/1/2000, Test Station, 090",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {len(accel_g)}, DT= {dt:.4f} SEC,"]
    vals = [f"{v:15.7E}" for v in accel_g]
    lines += ["".join(vals[i:i + 5]) for i in range(0, len(vals), 5)]
    path.write_text("\n".join(lines) + "\n")
    return path


def pulse_like(n, period, pga, dt=0.01):
    t = np.arange(n) * dt
    return pga * np.sin(2 * np.pi * t / period) * np.sin(np.pi * t / t[-1]) ** 2


@pytest.fixture
def folder(tmp_path):
    d = tmp_path / "suite"
    d.mkdir()
    write_at2(d / "b.AT2", pulse_like(120, 0.6, 0.3), title="B")
    write_at2(d / "a.at2", pulse_like(150, 0.8, 0.25), title="A")
    (d / "notes.txt").write_text("not a record")
    (d / "sub").mkdir()
    write_at2(d / "sub" / "c.AT2", pulse_like(100, 0.5, 0.2), title="C")
    return d


def test_folder_read_once_in_name_order_with_sha256(folder):
    s = read_suite(folder)
    assert [r.name.split(",")[0] for r in s.records] == ["A", "B"]  # a.at2, b.AT2; no subfolder
    for f, h, r in zip(s.files, s.sha256, s.records):
        assert h == hashlib.sha256(open(f, "rb").read()).hexdigest()
    assert s.records[1].pga_g == pytest.approx(np.max(np.abs(pulse_like(120, 0.6, 0.3))), rel=1e-6)
    assert s.records[0].times[1] == pytest.approx(0.01)
    d = s.to_dict()
    assert [x["sha256"] for x in d] == list(s.sha256) and d[0]["file"].endswith("a.at2")
    # files and folders mixed; the same file twice is refused
    both = read_records([folder / "sub" / "c.AT2", folder])
    assert len(both) == 3 and both.records[0].name.startswith("C")
    with pytest.raises(ArchInputError, match="twice"):
        read_records([folder, folder / "a.at2"])


def test_bad_folders(tmp_path):
    with pytest.raises(ArchInputError, match="no .AT2 file"):
        read_suite(tmp_path)
    with pytest.raises(ArchInputError, match="not a folder"):
        read_suite(tmp_path / "missing")


def test_fragility_on_a_folder_equals_its_files(folder, capsys):
    common = ["--radius", "2", "--thickness", "0.3", "--scales", "1:8:6", "--bootstrap", "0",
              "--json", "--no-progress"]
    assert main(["fragility", "--records", str(folder), *common]) == 0
    a = json.loads(capsys.readouterr().out)
    assert main(["fragility", "--records", str(folder / "a.at2"), str(folder / "b.AT2"),
                 *common]) == 0
    b = json.loads(capsys.readouterr().out)
    assert a["ida"] == b["ida"] and a["stripes"] == b["stripes"]
    assert [x["sha256"] for x in a["record_files"]] == [x["sha256"] for x in b["record_files"]]
    assert len(a["record_files"]) == 2 and a["im"] == "pga"
    # kept in --out and resumed from it: the same results
    for _ in range(2):
        assert main(["fragility", "--records", str(folder), *common, "--out",
                     str(folder.parent / "run")]) == 0
        kept = json.loads(capsys.readouterr().out)
        assert kept["ida"] == a["ida"] and kept["stripes"] == a["stripes"]
    assert (folder.parent / "run" / "manifest.json").exists()
    # in PGV: the same first-collapse scales, IM in m/s
    assert main(["fragility", "--records", str(folder), *common, "--im", "pgv"]) == 0
    c = json.loads(capsys.readouterr().out)
    assert [x["first_scale"] for x in c["ida"]["curves"]] == \
        [x["first_scale"] for x in a["ida"]["curves"]]
    assert c["im_units"] == "m/s" and c["ida"]["im_units"].startswith("m/s")
    # a bad Sa period names the field
    assert main(["fragility", "--records", str(folder), *common, "--im", "sa:x"]) == 2
    assert "im" in capsys.readouterr().err
