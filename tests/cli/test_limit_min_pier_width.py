"""archrock limit --min-pier-width H: the least width of two equal monolithic piers H m high
under the arch (archrock.statics.buttress.minimum_pier_width), in the table and the JSON."""

from __future__ import annotations

import json

import pytest

from archrock.cli import main

BASE = ("limit", "--radius", "5", "--embrace", "180", "--thickness", "0.8", "--voussoirs", "9")


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_min_pier_width_table_and_json(capsys):
    code, out, err = run(capsys, *BASE, "--min-pier-width", "4")
    assert code == 0, err
    line = next(ln for ln in out.splitlines() if "minimum pier width" in ln)
    assert "piers 4 m high: 1.1979 m" in line and "outer foot corner" in line
    code, out, err = run(capsys, *BASE, "--min-pier-width", "4", "--json")
    d = json.loads(out)["min_pier_width"]
    assert d["width"] == pytest.approx(1.197882, abs=1e-6)
    assert d["governed_by"] == "pier" and d["height"] == 4.0
    assert d["foot_point"] == pytest.approx([-4.6 - d["width"], -4.0], abs=1e-6)
    code, out, err = run(capsys, *BASE, "--min-pier-width", "0.05", "--json")
    assert json.loads(out)["min_pier_width"]["governed_by"] == "springing"


@pytest.mark.parametrize("extra,start", [
    (("--min-pier-width", "0"), "archrock: error: argument --min-pier-width"),
    (("--min-pier-width", "-2"), "archrock: error: argument --min-pier-width"),
    (("--min-pier-width", "4", "--pier-height", "3", "--pier-width", "2"),
     "archrock: error: --min-pier-width: cannot be combined with an arch on piers"),
])
def test_min_pier_width_refused_by_name(capsys, extra, start):
    code, out, err = run(capsys, *BASE, *extra)
    assert code == 2 and err.startswith(start), err
