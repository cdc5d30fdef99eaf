"""``archrock dem`` under a pulse states the routing of respond and the studies (issue 30): the
four-link run beside the engine is labelled "not valid here" where it does not hold; the engine
run, the figure and the animation report progress."""

from __future__ import annotations

import json

import pytest

from archrock.cli import main

PULSE = ["--pulse", "oppenheim", "--pulse-duration", "0.2"]


def test_dem_labels_the_four_link_run_not_valid_on_heavy_piers(on_heavy_piers, engine_calls,
                                                               capsys):
    argv = on_heavy_piers("dem", "--friction", "0.9")
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert out.startswith("Contact engine: heavy_piers, 12 voussoirs on two piers (found by "
                          "their geometry), Oppenheim pulse, friction MU = 0.9")
    assert ("governing model (--dynamics auto of respond and the studies): contact engine "
            "(single degree of freedom not valid") in out
    assert "  four-link (not valid here: single degree of freedom not valid: the piers" in out
    assert "    four-link outcome (not valid here): rest, peak phi 0.0414 rad" in out
    assert "\n  four-link: " not in out
    # the four-link run's impact law is the momentum law, and it says why
    assert "four-link impact law: momentum (the paper's law cannot be used on this arch" in out
    assert engine_calls[0]["friction"] == pytest.approx(0.9, abs=1e-15)
    assert main(argv + ["--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["dynamics"]["used"] == "engine" and d["dynamics"]["friction"] == pytest.approx(0.9)
    assert d["four_link"]["valid_here"] is False
    assert d["four_link"]["label"].startswith("four-link (not valid here: ")


def test_dem_on_oppenheim_keeps_the_plain_four_link_column(engine_calls, capsys):
    assert main(["dem", *PULSE, "--amplitude", "-1"]) == 0
    cap = capsys.readouterr()
    assert "governing model (--dynamics auto of respond and the studies): four-link model" \
        in cap.out
    assert "\n  four-link: " in cap.out and "not valid here" not in cap.out


def test_frame_progress_ends_at_100():
    from archrock.reports.animate import frame_progress

    lines = []
    cb = frame_progress(lines.append, "animation a.gif")
    for i in range(237):
        cb(i, 237)
    # the first frame says it started, then one line per 10%
    assert len(lines) == 11 and lines[0] == "animation a.gif: frame 1/237 (0%)"
    assert lines[-1] == "animation a.gif: frame 237/237 (100%)"
    assert frame_progress(None, "x") is None


def test_engine_progress_lines_end_at_100():
    """The engine's run: a line per 10% of its longest (and every 5 s of wall time), the
    last at 100% with how it ended."""
    pytest.importorskip("pymunk")
    from archrock.contact import EngineSettings
    from archrock.contact.motion import engine_respond
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse

    lines = []
    res = engine_respond(oppenheim_arch(), oppenheim_pulse(-0.2, 0.2),
                         EngineSettings(steps_per_T=150, iterations=20), t_end=0.5,
                         t_free=1.0, progress=lines.append)
    assert lines[-1] == f"engine: 100% ({res.status} at t = {res.t_final:.2f} s)"
    assert 1 <= len(lines) <= 12 or all("engine: t = " in ln for ln in lines[:-1])


def test_ramp_compares_with_the_friction_analysis_where_the_joints_slide(capsys):
    """A deep five-voussoir arch slides before it rocks at mu = 0.8 (friction LP 0.9247 < the
    no-sliding 1.0972): dem --ramp compares the engine with the friction analysis, within 0.5%,
    and says so, instead of a -16% 'error' against the no-sliding k."""
    argv = ["dem", "--radius", "10", "--embrace", "160", "--thickness", "4", "--voussoirs", "5",
            "--ramp", "--no-progress"]
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    for k in ("k_l", "k_r"):
        assert d["compared_with"][k]["analysis"] == "friction LP"
        assert d["compared_with"][k]["k"] < d["limit"][k]
        assert abs(d["relative_error"][k]) < 0.005
    assert d["l"]["mode"] == "sliding"
