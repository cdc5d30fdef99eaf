"""`archrock fragility` on an arch one degree of freedom cannot follow (issue 31): the IDA by the
contact engine instead of a refusal, the model and the reason stated, "dynamics" in the JSON;
--dynamics fourlink keeps the four-link study; what the engine cannot run is refused by field."""

import json

import numpy as np
import pytest

from archrock.cli import main


@pytest.fixture(scope="module")
def sine_record(tmp_path_factory):
    """One full sine of 2 s and 1 g amplitude, as a two-column file (time [s], accel [g])."""
    t = np.linspace(0.0, 2.0, 201)
    rec = tmp_path_factory.mktemp("rec") / "sine2.txt"
    np.savetxt(rec, np.column_stack([t, np.sin(np.pi * t)]))
    return rec


def _run(capsys, heavy_piers_file, rec, *extra):
    code = main(["fragility", "--geometry", str(heavy_piers_file), "--records", str(rec),
                 "--scales", "0.05,2", "--bootstrap", "0", "--no-progress", *extra])
    out, err = capsys.readouterr()
    return code, out, err


def test_heavy_piers_run_by_the_engine_json(capsys, heavy_piers_file, sine_record):
    code, out, err = _run(capsys, heavy_piers_file, sine_record, "--json", "--levels", "0.5,1")
    assert code == 0, err
    d = json.loads(out)
    assert d["model"] == "engine" and d["dynamics"]["used"] == "engine"
    assert "single degree of freedom not valid" in d["dynamics"]["reason"]
    assert d["ida"]["how"] == "contact engine"
    assert d["ida"]["collapsed"] == [[0, 1]]  # 0.05 g: below activation; 2 g: far above
    assert d["ida"]["records"][0]["first_scale"] == pytest.approx(2.0)
    assert d["stripes"] is None and d["unused_options"] == ["--levels"]


def test_heavy_piers_report_names_the_engine(capsys, heavy_piers_file, sine_record):
    code, out, err = _run(capsys, heavy_piers_file, sine_record)
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0].startswith("dynamics: contact engine (single degree of freedom not valid")
    assert "first collapse 2.0000 g (scale 2)" in out
    assert "stripes: not run on the contact engine's path" in out


@pytest.mark.parametrize("extra, message", [
    (("--friction", "none"), "archrock: error: friction: none (sliding excluded) cannot be "
                             "modelled by the contact engine"),
    (("--samples", "3"), "archrock: error: samples: 3; the contact engine's fragility"),
    (("--out", "kept"), "archrock: error: out: "),
])
def test_what_the_engine_cannot_run_is_refused(capsys, heavy_piers_file, sine_record, extra,
                                               message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, heavy_piers_file, sine_record, *extra)
    assert code == 2 and out == ""
    assert err.startswith(message) and len(err.splitlines()) == 1


def test_dynamics_fourlink_keeps_the_four_link_study(capsys, heavy_piers_file, sine_record):
    code, out, err = _run(capsys, heavy_piers_file, sine_record, "--dynamics", "fourlink",
                          "--levels", "0.5,1")
    assert code == 0, err
    assert "WARNING single degree of freedom not valid" in err
    assert "contact engine" not in out and out.splitlines()[-1].startswith("stripes: ")
