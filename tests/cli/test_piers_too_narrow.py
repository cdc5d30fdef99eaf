"""An arch that cannot stand on its piers: the outcome names the piers and the least width that
carries it (archrock.statics.buttress.piers_cannot_stand, in the library's own message: every
command, the assessment report and the app say the same)."""

from __future__ import annotations

import json

from archrock.cli import main

NARROW = ["--pier-height", "8", "--pier-width", "1.6"]
LINE = ("archrock: outcome: arch: it cannot stand on its piers (two piers 1.6 m wide, 8 m high) "
        "under its own weight (k_l = -0.1211, k_r = -0.1211); on rigid supports it stands, and "
        "piers 8 m high carry it from 2.3531 m wide: give the piers a width of 2.354 m or more "
        "(the least pier width, archrock.statics.buttress.minimum_pier_width; docs/piers.md)")
SEMICIRCLE = ["--radius", "5", "--embrace", "180", "--thickness", "0.8", "--voussoirs", "9"]


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


def test_tall_slender_piers_get_the_width_min_pier_width_gives(capsys):
    # the case: 15 m x 1.5 m piers under the semicircle; --min-pier-width 15: 1.7113 m
    code, out, err = run(capsys, "limit", *SEMICIRCLE, "--pier-height", "15", "--pier-width",
                         "1.5")
    assert code == 3 and out == ""
    assert "cannot stand on its piers (two piers 1.5 m wide, 15 m high)" in err
    assert "carry it from 1.7113 m wide: give the piers a width of 1.712 m or more" in err
    assert "increase the thickness" not in err
    code, out, _ = run(capsys, "limit", *SEMICIRCLE, "--min-pier-width", "15")
    assert code == 0 and "piers 15 m high: 1.7113 m" in out


def test_buttresses_and_unequal_piers_are_named(capsys):
    code, _, err = run(capsys, "limit", *SEMICIRCLE, "--pier-height", "15", "--pier-width",
                       "1.5", "--pier-courses", "3", "--pier-batter", "0.01")
    assert code == 3
    assert "on its buttresses (two buttresses of 3 courses, 1.5 m wide, 15 m high, batter " \
           "0.01)" in err and "give the buttresses a width of 1.564 m or more" in err
    code, _, err = run(capsys, "limit", *SEMICIRCLE, "--pier-height", "15", "--pier-width",
                       "1.5", "--right-pier-width", "1.6")
    assert code == 3
    assert "on its piers (left: 1.5 m wide, 15 m high; right: 1.6 m wide, 15 m high)" in err
    assert "its piers cannot carry its thrust" in err


def test_assessment_and_library_give_the_same_text():
    import pytest

    from archrock.errors import CannotStandError
    from archrock.geometry import nominal_arch, with_piers
    from archrock.statics.limit import limit_analysis

    arch = with_piers(nominal_arch(5.0, 180.0, 0.8, 9), 15.0, 1.5)
    with pytest.raises(CannotStandError, match=r"on its piers .* give the piers a width of "
                                               r"1\.712 m or more"):
        limit_analysis(arch)
