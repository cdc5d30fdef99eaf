"""curves, ensemble and the four-link-only commands route with the command's --friction
(issue 30): the same arch gets the same routing everywhere, and the choice is in the JSON."""

from __future__ import annotations

import argparse
import json

import pytest

from archrock.cli import main
from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch

PULSE = ["--pulse", "oppenheim", "--amplitude", "-1", "--pulse-duration", "0.2"]


class Captured(Exception):
    """Raised by a stand-in once it has seen what the command passed."""


def test_curves_json_has_the_choice(capsys):
    assert main(["curves", "--durations", "0.5", "--n-scan", "4", "--a-max", "1",
                 "--json", "--no-progress"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["dynamics"]["used"] == "fourlink"
    assert d["dynamics"]["friction"] == pytest.approx(0.8, abs=1e-15)
    assert d["dynamics"]["friction_needed"]["l"] == pytest.approx(0.49513, abs=1e-4)


def test_curves_low_friction_runs_the_engine_at_that_friction(monkeypatch):
    """Oppenheim's joints slide at mu 0.4 (the collapse needs 0.495): the engine's curve, run
    at 0.4."""
    from archrock.studies import enginestudy

    seen = {}

    def engine_collapse_curve(arch, durations, kind, sign, **kw):
        seen["friction"] = kw["run"].settings.friction
        raise Captured

    monkeypatch.setattr(enginestudy, "engine_collapse_curve", engine_collapse_curve)
    with pytest.raises(Captured):
        main(["curves", "--durations", "0.5", "--friction", "0.4", "--no-progress"])
    assert seen["friction"] == pytest.approx(0.4, abs=1e-15)


def test_ensemble_routes_at_its_friction(heavy_piers_file, monkeypatch, capsys):
    """The heavy piers' engine ensemble runs at --friction; none is refused there (the engine
    cannot exclude sliding) before any work."""
    from archrock.studies.ensemble import engine as ensemble_engine

    seen = {}

    def engine_ensemble(config, engine=None, *, dynamics=None, progress=None):
        seen["friction"], seen["dynamics"] = engine.settings.friction, dynamics
        raise Captured

    monkeypatch.setattr(ensemble_engine, "engine_ensemble", engine_ensemble)
    argv = ["ensemble", "--geometry", str(heavy_piers_file), "--samples", "2", *PULSE,
            "--no-progress"]
    with pytest.raises(Captured):
        main(argv + ["--friction", "1.5"])
    assert seen["friction"] == pytest.approx(1.5, abs=1e-15)
    assert seen["dynamics"].engine and seen["dynamics"].friction == pytest.approx(1.5)
    assert main(argv + ["--friction", "none"]) == 2
    assert "archrock: error: --friction: none (sliding excluded)" in capsys.readouterr().err


def test_ensemble_json_has_the_choice(capsys):
    assert main(["ensemble", "--samples", "2", "--batch-size", "2", *PULSE, "--json",
                 "--no-progress"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["dynamics"]["used"] == "fourlink" and d["dynamics"]["requested"] == "auto"
    assert d["dynamics"]["friction"] == pytest.approx(0.8, abs=1e-15)


def test_fourlink_only_commands_route_at_their_friction():
    """check_fourlink (fragility, sensitivity, defects) refuses Oppenheim's arch at mu 0.4
    (its joints slide) and returns the choice where the four-link model holds."""
    from archrock.cli.fourlinkonly import check_fourlink

    with pytest.raises(ArchInputError, match="slide"):
        check_fourlink(oppenheim_arch(), argparse.Namespace(dynamics="auto", friction=0.4),
                       "fragility")
    choice = check_fourlink(oppenheim_arch(), argparse.Namespace(dynamics="auto", friction=0.8),
                            "fragility")
    assert choice.used == "fourlink" and choice.friction == pytest.approx(0.8, abs=1e-15)
