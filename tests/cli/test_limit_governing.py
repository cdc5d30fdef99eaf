"""``archrock limit`` states the governing capacity at one friction (issue 30), and
``archrock assess --friction`` takes the same values."""

from __future__ import annotations

import json

import pytest

from archrock.cli import main


def run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def _governing_lines(out: str) -> list[str]:
    lines = out.splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith("Governing capacity"))
    return lines[i:]


def test_default_friction_is_stated_and_no_sliding_governs(capsys):
    rc, out, err = run(capsys, "limit")
    assert rc == 0, err
    gov = _governing_lines(out)
    assert gov[0] == "Governing capacity, friction mu = 0.8 (the default; --friction MU|none)"
    assert gov[1].startswith("  governing: k = 0.370010 g (limit analysis (no sliding), both "
                             "directions, no tension; no crushing; no sliding (checked against "
                             "mu = 0.8))")
    assert gov[2] == "  left out: contact engine ramp: not run by limit: archrock dem --ramp"
    # the other lines are those of 0.6 (k to 4 decimals, the friction needed)
    assert "k = min(k_l, k_r) = 0.3700" in out and "M_l 0.4951, M_r 0.4951" in out


def test_low_friction_sliding_governs(capsys):
    rc, out, err = run(capsys, "limit", "--friction", "0.4")
    assert rc == 0, err
    gov = _governing_lines(out)
    assert gov[0] == "Governing capacity, friction mu = 0.4 (--friction)"
    assert gov[1].startswith("  governing: k = 0.263759 g (limit analysis with friction "
                             "mu = 0.4, both directions")
    d = json.loads(run(capsys, "limit", "--friction", "0.4", "--json")[1])
    assert d["governing"]["governing"]["value"] == pytest.approx(0.2638, abs=5e-5)
    assert d["governing"]["friction"] == pytest.approx(0.4, abs=1e-15)
    assert d["friction_k_l"] == pytest.approx(0.2638, abs=5e-5)  # 0.6's keys kept


def test_friction_none_is_heyman_stated(capsys):
    rc, out, err = run(capsys, "limit", "--friction", "none", "--json")
    assert rc == 0, err
    d = json.loads(out)
    g = d["governing"]
    assert g["friction"] is None and g["friction_stated"].startswith("none: sliding excluded")
    assert g["governing"]["value"] == pytest.approx(0.370010, abs=5e-7)
    assert [x["name"] for x in g["left_out"]] == ["limit analysis with friction",
                                                  "contact engine ramp"]
    assert "friction_mu" not in d  # no friction analysis ran


@pytest.mark.parametrize("bad", ["0", "-1", "nan", "abc"])
def test_bad_friction_is_one_line_exit_2(capsys, bad, tmp_path):
    for cmd in (["limit"], ["assess", "--out", str(tmp_path / "r.html")]):
        rc, out, err = run(capsys, *cmd, "--friction", bad)
        assert rc == 2 and "--friction" in err and "'none'" in err
        assert "Traceback" not in err and len(err.strip().splitlines()) <= 3


def test_friction_only_arch_governs_by_friction(capsys):
    """An arch that only friction brings to a mechanism: the friction analysis governs, the
    no-sliding analysis is left out with its reason."""
    flat = ["--radius", "10", "--embrace", "70", "--thickness", "2", "--voussoirs", "7"]
    d = json.loads(run(capsys, "limit", *flat, "--friction", "0.3", "--json")[1])
    g = d["governing"]
    assert g["governing"]["analysis"] == "limit analysis with friction mu = 0.3"
    assert g["governing"]["value"] == pytest.approx(d["friction_k_l"], rel=1e-12)
    assert "no mechanism" in g["left_out"][0]["why"]
