"""``archrock limit --friction`` on an arch that only friction brings to a mechanism."""

from __future__ import annotations

import json

import pytest

from archrock.cli import main

FLAT = ["--radius", "10", "--embrace", "70", "--thickness", "2", "--voussoirs", "7"]


def run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.fixture(scope="module")
def library():
    from archrock.geometry.circular import nominal_arch
    from archrock.statics.friction import friction_analysis

    return friction_analysis(nominal_arch(10, 70, 2, 7), 0.3)


def test_friction_answers_without_frictionless_mechanism(capsys, library):
    rc, out, err = run(capsys, "limit", *FLAT, "--friction", "0.3")
    assert rc == 0, err
    assert "No frictionless mechanism: no mechanism opens under horizontal forces" in out
    line = next(ln for ln in out.splitlines()
                if ln.startswith("  k = min(k_l, k_r) with friction"))
    assert abs(float(line.split("= ")[2].split()[0]) - library.k) < 1e-4
    assert library.l.sliding_governs and library.r.sliding_governs


def test_friction_only_json_matches_library(capsys, library):
    rc, out, err = run(capsys, "limit", *FLAT, "--friction", "0.3", "--json")
    assert rc == 0, err
    d = json.loads(out)
    assert d["frictionless_mechanism"] is False
    assert abs(d["k_l"] - library.l.multiplier) < 1e-9
    assert abs(d["k_r"] - library.r.multiplier) < 1e-9
    assert 2.0 < d["k"] < 2.1  # a flat thick arch: its joints slide near k ~ 2
    assert d["sliding_governs_l"] is True and d["sliding_governs_r"] is True
    assert d["mechanism_l"].startswith("sliding at joint")
    assert d["friction_joints_l"] == list(library.l.joints)


def test_without_friction_the_outcome_names_the_flag(capsys):
    rc, _, err = run(capsys, "limit", *FLAT)
    assert rc == 3
    assert err.startswith("archrock: outcome: arch: no mechanism opens")
    assert "--friction MU gives the multipliers at which its joints slide" in err
    assert len(err.strip().splitlines()) == 1


def test_capacity_on_an_arch_without_frictionless_mechanism(capsys):
    """--capacity is answered where no mechanism opens under horizontal forces (it stopped on
    the limit analysis's outcome before)."""
    rc, out, err = run(capsys, "limit", *FLAT, "--capacity", "spread", "--json")
    assert rc == 0, err
    d = json.loads(out)
    assert d["frictionless_mechanism"] is False and d["k"] is None
    assert 2.2 < d["capacity"]["capacity"] < 2.4


def test_closure_of_a_flat_arch_says_why_there_is_no_capacity(capsys):
    rc, _, err = run(capsys, "limit", *FLAT, "--capacity", "closure")
    assert rc == 3
    assert err.startswith("archrock: outcome: arch: a closure of the right support cannot bring "
                          "this arch to a mechanism: a straight line of thrust fits inside it")
    assert "horizontal forces" not in err
