"""An arch that cannot stand on its piers: the outcome names the piers and the least width that
carries it (archrock.cli.options.piers_too_narrow, any command that builds the arch)."""

from __future__ import annotations

import json

from archrock.cli import main

NARROW = ["--pier-height", "8", "--pier-width", "1.6"]
LINE = ("archrock: outcome: arch: it cannot stand on its piers (blocks 0 and 8: 1.6 m wide, 8 m "
        "high) under its own weight (k_l = -0.1211, k_r = -0.1211); on rigid supports it stands, "
        "and piers 8 m high carry it from 2.3531 m wide: give --pier-width 2.354 or more "
        "(docs/piers.md)")


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_limit_names_piers_and_width(capsys):
    code, out, err = run(capsys, "limit", *NARROW)
    assert code == 3 and out == ""
    assert err.strip() == LINE


def test_the_width_it_names_carries_the_arch(capsys):
    code, out, err = run(capsys, "limit", "--pier-height", "8", "--pier-width", "2.354",
                         "--json")
    assert code == 0, err
    assert 0 < json.loads(out)["k"] < 0.01  # just standing: the piers at their least width


def test_ensemble_says_the_same(capsys):
    code, _, err = run(capsys, "ensemble", "--samples", "2", "--no-progress", *NARROW)
    assert code == 3
    assert err.strip().splitlines()[-1] == LINE


def test_arch_that_falls_on_rigid_ground_keeps_its_message(capsys):
    # t/R 0.05 (Oppenheim's embrace): no pier helps, the advice is the thickness
    code, _, err = run(capsys, "limit", "--thickness", "0.5", *NARROW)
    assert code in (2, 3)
    assert "on its piers" not in err
